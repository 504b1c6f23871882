#include <cutroute/core/version.hpp>

#include <cstdlib>

namespace cutroute {

const char* version() { return CUTROUTE_VERSION; }

const char* data_dir() {
  if (const char* env = std::getenv("CUTROUTE_DATA_DIR"); env && *env) return env;
  return CUTROUTE_DATA_DIR;
}

}  // namespace cutroute
