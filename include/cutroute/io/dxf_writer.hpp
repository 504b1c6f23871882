// write_dxf(): a small ASCII DXF (AC1015) writer for contours with layers, read back exactly by read_dxf.
#pragma once

#include <string>
#include <vector>

#include <cutroute/geometry/contour.hpp>

namespace cutroute::io {

struct DxfWriteEntity {
  geometry::Contour path;  // [mm]
  std::string layer;       // empty = "0"
};

struct DxfWriteOptions {
  std::string units = "mm";  // "mm", "cm", "m", "in", "ft": coordinates are written in this unit
                             // and $INSUNITS says so (anything else is written as mm)
};

// One LWPOLYLINE per contour (bulges, closed flag), except a closed contour of 2 vertices with
// equal bulges ±1, which is a full circle and is written as a CIRCLE (read back as the
// counter-clockwise circle starting at angle 0). Numbers are written in shortest round-trip
// form, so reading an "mm" file back gives the same doubles. Contours without vertices are left out.
std::string write_dxf(const std::vector<DxfWriteEntity>& entities, const DxfWriteOptions& options);

}  // namespace cutroute::io
