#include "progress_line.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <iostream>

#include <cutroute/core/number_format.hpp>

namespace cutroute::cli {

namespace {
// The terminal's width on stderr, 80 when it does not say.
std::size_t terminal_columns() {
  winsize w{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
  return 80;
}
}  // namespace

std::string fit_progress_line(const std::string& name, const std::string& rest, std::size_t columns) {
  // A line as wide as the terminal wraps, and "\r" then rewrites only its last row: a long path
  // filled the screen with copies of the line. The name gives way first, from its front (the file
  // name at the end says most), then the rest is cut.
  const std::size_t room = columns > 1 ? columns - 1 : 0;
  if (name.size() + 2 + rest.size() <= room) return name + ": " + rest;
  const std::size_t left = room > rest.size() + 2 ? room - rest.size() - 2 : 0;
  if (left >= 4) return "..." + name.substr(name.size() - (left - 3)) + ": " + rest;
  return rest.substr(0, room);
}

ProgressFn ProgressLine::for_job(const std::string& name) {
  if (!on_) return {};
  return [this, name](const ProgressEvent& e) {
    std::lock_guard lock(mu_);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    std::string rest(e.stage);
    if (e.fraction >= 0.0) {
      rest += ' ';
      rest += format_fixed(100.0 * e.fraction, 0);
      rest += " %";
    }
    if (e.best) rest += "  best " + format_fixed(*e.best, decimals_);
    rest += "  " + format_fixed(std::chrono::duration<double>(now - t0_).count(), 1) + " s";
    // "\x1b[K" erases what a longer line before left to the right (ANSI, as every terminal has).
    std::cerr << '\r' << fit_progress_line(name, rest, terminal_columns()) << "\x1b[K" << std::flush;
  };
}

void ProgressLine::done() {
  if (on_) std::cerr << "\r\x1b[K" << std::flush;
}

}  // namespace cutroute::cli
