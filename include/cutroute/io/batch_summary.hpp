// batch_summary_csv(): the table of a batch of optimized nests, one row per sheet and their totals, as CSV.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cutroute::io {

// One nest of a batch: its optimize report, or the error that stopped it.
struct BatchEntry {
  std::string nest;            // the DXF file as given
  std::string program;         // the program written ("" when none was)
  nlohmann::json report;       // null when the nest failed
  std::string error;           // the message when it failed
  bool not_started = false;    // Ctrl-C or SIGTERM stopped the batch before this nest was begun
};

// Columns: nest, status (ok / error / not started), technique, material, thickness_mm, pierces,
// cut_length_mm, rapid_length_mm, frames, t_cut_s, t_cut_const_speed_s, cost, cost_unit, route
// ("optimal", "gap Z %" or empty), program, error, warnings (the report's warnings counted by
// code, "chain.open:2 tabs.on_a_neighbours_cut:1": what to look at before cutting that sheet);
// one row per entry in the given order, then a
// row "total" summing the numbers of the sheets that were cut (the cost only when every sheet has
// the same unit). Lengths in mm, times in s, as in the reports; fields with a comma, quote or
// line break are quoted (RFC 4180).
std::string batch_summary_csv(const std::vector<BatchEntry>& entries);

}  // namespace cutroute::io
