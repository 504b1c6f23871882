// Iso-lines of a scalar field sampled on a regular grid, by marching squares (saddles resolved by the
// cell-centre mean), joined into polylines in fractional grid-index coordinates.
#pragma once

#include <array>
#include <vector>

namespace cutroute::machining {

struct IsoLine {
  std::vector<std::array<double, 2>> pts;  // (i, j) fractional grid indices
  bool closed = false;
};

// z is row-major with z[j·nx + i] at column i (x) and row j (y). Cells with a non-finite corner are
// skipped, so an iso-line stops where the field is undefined.
std::vector<IsoLine> iso_lines(const std::vector<double>& z, int nx, int ny, double level);

}  // namespace cutroute::machining
