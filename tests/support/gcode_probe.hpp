// GcodeProbe: a tiny, independent G-code reader for tests: it re-parses what the writer wrote.
#pragma once

#include <string>
#include <vector>

namespace cutroute::test {

// Deliberately separate from the product's reader (nc/): tests check the writer against a
// second implementation. Supports G0/G1/G2/G3 (X Y, I J incremental, or R), G20/G21, G90,
// M3/M4 beam on, M5 beam off, N numbers, ( ) and ; comments. Arcs are measured exactly.
struct ProbeMove {
  bool rapid = false;
  bool beam_on = false;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [mm]
  double cx = 0, cy = 0;                  // arc centre [mm]
  int arc = 0;                            // 0 line, +1 CCW (G3), -1 CW (G2)
  double length = 0;                      // [mm]
  int line = 0;                           // 1-based line in the program
  bool compensated = false;               // under G41/G42 (controller kerf compensation)
};

struct ProbeResult {
  std::vector<ProbeMove> moves;
  int pierces = 0;             // beam off -> on transitions
  double cut_length = 0;       // beam on, G1/G2/G3 [mm]
  double rapid_length = 0;     // G0 [mm]
  double max_arc_radius_error = 0;  // |r_start - r_end| over all arcs [mm]
  int frames = 0;              // lines that hold a block (not blank, comment-only or %)
  bool cut_with_beam_off = false;   // a G1/G2/G3 with the beam off
  bool ended = false;          // M2 or M30 seen
  std::vector<std::string> errors;
};

ProbeResult probe_gcode(const std::string& program);

// Point at fraction t in [0,1] of a move (for "which contour does this cut lie on" checks).
void probe_point(const ProbeMove& m, double t, double& x, double& y);

// Exact distance from (x, y) to a move (a line, or an arc within its sweep, else its nearer end) [mm].
double probe_distance(const ProbeMove& m, double x, double y);

}  // namespace cutroute::test
