// Number formatting for text outputs (G-code, SVG, reports): fixed decimals, no trailing zeros, never "-0".
#pragma once

#include <string>

namespace cutroute {

// Appends v rounded to `decimals` places: trailing zeros and a trailing point are trimmed and
// a result that rounds to zero is written "0" (never "-0"). Uses std::to_chars into a fixed
// buffer (no locale, no allocation beyond the append).
void append_fixed(std::string& out, double v, int decimals);
std::string format_fixed(double v, int decimals);
// The shortest text that reads back to the same double ("nan", "inf", "-inf" otherwise): for
// messages that quote a value exactly, e.g. a limit just exceeded.
std::string format_shortest(double v);

}  // namespace cutroute
