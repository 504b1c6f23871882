// Private pre-scan of a DXF text: validates the group-code/value structure, records each entity's
// line, handle and layer, and builds the sanitised text that dxflib is allowed to parse.
//
// Why this exists (dxflib 3.26 falls short in four ways):
// - it reports no line numbers and keeps handles as int, so diagnostics could not name a line;
// - it trusts the file: a group 90/72/73/74 count drives `new double[n]`, a bulge (42) before the
//   first LWPOLYLINE vertex writes before its array, a line longer than 1024 characters puts the
//   stream into a fail state that loops forever, and non-numeric values silently become 0;
// - it splits lines on LF only (CR-only files would be one line);
// - it parses TABLES, HATCH, MTEXT, ... which we never use and where real files are malformed
//   (DeepNest's TABLES section).
// So the scan checks everything first and hands dxflib only the curve entities (plus INSERT)
// of the BLOCKS and ENTITIES sections, LF-terminated, each with the byte offset at which dxflib
// will report it; the reader maps dxflib's callbacks back to scan records through that offset.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/geometry/vec2.hpp>

namespace cutroute::io::detail {

struct ScanEntity {
  std::string type;             // entity type as written ("LINE", "MTEXT", ...)
  long line = 0;                // 1-based line of its "0" group code
  std::string handle;           // group 5, may be empty
  std::string layer = "0";      // group 8
  int block = -1;               // index in ScanResult::blocks, -1 = ENTITIES section
  int owner = -1;               // VERTEX/SEQEND/ATTRIB: index of the POLYLINE/INSERT they belong to
  bool paperspace = false;      // group 67 = 1
  bool invisible = false;       // group 60 = 1: the CAD program does not draw it
  double elevation = 0;         // the OCS z of an ARC, CIRCLE, INSERT, POLYLINE (first group 30) or LWPOLYLINE (38)
  bool has_elevation = false;
  int flags = 0;                // first group 70 (polyline/spline flags)
  bool forwarded = false;       // handed to dxflib
  int spline = -1;              // SPLINE: index in ScanResult::splines
  std::string block_name;       // INSERT: group 2
};

struct ScanBlock {
  std::string name;             // group 2
  long line = 0;                // line of its "0 BLOCK"
  geometry::Vec2 base;          // base point [drawing units]
  int flags = 0;                // group 70 (4 = external reference)
  std::vector<int> entities;    // top-level entity indices (sub-entities excluded)
};

// The number arrays of a SPLINE, in file order [drawing units]. dxflib converts every number
// through a std::stringstream (about half a microsecond each); on spline-heavy drawings
// (d2g_DRAAK: 1186 splines, 100 000 knots and control points) that alone took 70 ms of the
// 0.3 s `inspect` budget. The scan parses every number anyway to validate it, so it keeps these;
// dxflib still reads each SPLINE's degree, flags and end tangents.
struct ScanSpline {
  std::vector<double> knots;            // group 40
  std::vector<geometry::Vec2> control;  // groups 10/20
  std::vector<double> weights;          // group 41
  std::vector<geometry::Vec2> fit;      // groups 11/21
};

struct ScanResult {
  std::vector<ScanEntity> entities;  // BLOCKS and ENTITIES contents, file order
  std::vector<ScanBlock> blocks;
  std::vector<int> modelspace;       // top-level entities of the ENTITIES section
  std::vector<ScanSpline> splines;
  // Layers the LAYER table has turned off (colour < 0) or frozen (flag 1): the CAD program shows
  // nothing of them. Name as written, and "off", "frozen" or "off and frozen".
  std::vector<std::pair<std::string, std::string>> hidden_layers;
  std::optional<int> insunits;       // $INSUNITS
  std::optional<int> measurement;    // $MEASUREMENT
  std::string dxflib_text;           // sanitised text for dxflib (LF line ends)
  // For each "0" group in dxflib_text, the byte offset just after its type line and the scan
  // entity it starts (-1 for the closing ENDSEC): dxflib reports an entity when it reads the
  // next "0" group, so the stream position at a callback identifies the entity before it.
  std::vector<std::size_t> zero_offsets;
  std::vector<int> zero_entities;
  std::vector<Diagnostic> warnings;
};

// Millimetres per drawing unit for a $INSUNITS code we accept; nullopt for others.
std::optional<double> insunits_mm(int code);
const char* insunits_name(int code);

// Scans `content`. Coordinates (group codes 10..39) inside BLOCKS and ENTITIES must stay within
// max_abs_units (the coordinate limit expressed in drawing units, given the file's units: the
// scan asks `mm_per_unit(insunits, measurement)` once the HEADER has been read).
using UnitsRule = double (*)(std::optional<int> insunits, std::optional<int> measurement, const void* ctx);
Result<ScanResult> scan_dxf(std::string_view content, const std::string& file, UnitsRule mm_per_unit,
                            const void* units_ctx);

}  // namespace cutroute::io::detail
