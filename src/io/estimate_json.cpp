#include <cutroute/io/estimate_json.hpp>

namespace cutroute::io {

nlohmann::json breakdown_json(const cost::TimeEstimate& e) {
  return {{"cutting_s", e.cutting_s},
          {"rapid_s", e.rapid_s},
          {"pierce_s", e.pierce_s},
          {"dwell_s", e.dwell_s},
          {"pierce_replaced_s", e.pierce_replaced_s},
          {"feed_off_s", e.feed_off_s},
          {"head_s", e.head_s},
          {"total_s", e.total_s}};
}

}  // namespace cutroute::io
