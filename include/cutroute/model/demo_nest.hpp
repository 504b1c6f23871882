// Generated demo nests: the bundled example sheet (like the source paper's 2000×1000 mm example).
#pragma once

#include <vector>

#include <cutroute/model/nest.hpp>

namespace cutroute::model {

// A 2000 × 1000 mm sheet (border on layer "SHEET") with 14 parts and 21 cut contours on layer
// "CUT", like the worked example of Petunin et al.: 4 plates 400 × 250 mm with rounded corners
// and one Ø80 hole, 3 flanges Ø300 with a Ø100 bore, and 7 L-brackets 250 × 300 mm with a
// filleted inner corner, six of them placed in three pairs 5 mm apart (close enough to be
// chain-cut with one pierce per pair). Outer contours counter-clockwise, holes clockwise.
std::vector<SourceContour> make_demo_sheet();

// The paper example's gaps and sizes, for tests that check the generated sheet.
inline constexpr double kDemoSheetWidthMm = 2000.0;
inline constexpr double kDemoSheetHeightMm = 1000.0;
inline constexpr double kDemoChainGapMm = 5.0;

}  // namespace cutroute::model
