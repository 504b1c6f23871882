// DrawingUnit and format_position(): places named in messages in the drawing's own unit, so that they can be found in it.
#pragma once

#include <string>

namespace cutroute {

// The unit the drawing's numbers are read in (its header, or --units). Geometry stays in mm
// inside; only the positions messages name are given back in this unit: a shop that drew a part
// in inches looks for "(28.6274, 6.0966) in", not for the 727.136 mm the program knows it by.
struct DrawingUnit {
  double mm_per_unit = 1.0;  // [mm per drawing unit]
  std::string name = "mm";   // "mm", "in", "ft", "cm", ... (io::DxfDrawing::unit_name)
};

// "(x, y)" of a point given in mm [mm]: in millimetres with 3 decimals and no unit named (as
// every message wrote it before), in another unit converted, to the decimals that keep about a
// micrometre (4 for inches, 5 for feet), with the unit after it: "(28.6274, 6.0966) in".
std::string format_position(double x_mm, double y_mm, const DrawingUnit& unit);

}  // namespace cutroute
