// Readers for solver instance files: GTSPLIB .gtsp, TSPLIB SOP .sop and the PCGLNS text format.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <cutroute/core/result.hpp>
#include <cutroute/solve/problem.hpp>

namespace cutroute::io {

// gtsp:   TSPLIB + GTSP_SETS / GTSP_SET_SECTION; closed tour, start cluster = set 1.
// sop:    TSPLIB SOP; one singleton cluster per node, open path from node 1 to node n; an entry
//         c[i][j] = -1 means j must precede i (and forbids the arc i -> j).
// pcglns: TYPE PCGLNS (or PCGTSP): EXPLICIT FULL_MATRIX where -1 forbids an arc, GTSP_SET_SECTION,
//         GTSP_SET_ORDERING lines "A B1 B2 ... -1" (set A before each B_i), START_GROUP_SECTION;
//         closed tour from the start group. docs/SOLVER.md shows an example.
enum class InstanceFormat { gtsp, sop, pcglns };
const char* to_string(InstanceFormat f);

struct Instance {
  std::string name;        // NAME field (file stem when absent)
  InstanceFormat format = InstanceFormat::gtsp;
  solve::Problem problem;  // node k of the file (1-based) is NodeId(k - 1), set k is ClusterId(k - 1)
};

// Reads `path`; the format comes from the extension (.gtsp, .sop, .pcglns), else from TYPE.
// Errors name the file and line ("x.gtsp:12: error: ..."). Never throws on bad content.
Result<Instance> read_instance(const std::string& path);

// Parses text already in memory; `file` is only used in messages and for the format by extension.
Result<Instance> parse_instance(std::string_view text, const std::string& file,
                                std::optional<InstanceFormat> format = std::nullopt);

}  // namespace cutroute::io
