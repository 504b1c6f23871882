// breakdown_json(): the time breakdown of an estimate, the same object in the optimize report and in `estimate --json`.
#pragma once

#include <nlohmann/json.hpp>

#include <cutroute/cost/estimate.hpp>

namespace cutroute::io {

// {cutting_s, rapid_s, pierce_s, dwell_s, pierce_replaced_s, feed_off_s, head_s, total_s} [s]:
// eq. 10's three terms, then what lies outside it; total_s is what the machine takes in all.
nlohmann::json breakdown_json(const cost::TimeEstimate& e);

}  // namespace cutroute::io
