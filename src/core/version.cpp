#include <cutroute/core/version.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace cutroute {

const char* version() { return CUTROUTE_VERSION; }

namespace {

// A copied or installed binary finds its data beside it (`cutroute` + `data/`, or the install
// layout bin/ + share/cutroute/data/) before the source tree it was built from, which another
// machine does not have. Read once: the answer cannot change during a run.
std::string find_data_dir() {
  if (const char* env = std::getenv("CUTROUTE_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path dir = exe.parent_path();
    for (const auto& candidate : {dir / "data", dir / ".." / "share" / "cutroute" / "data"})
      if (std::filesystem::is_regular_file(candidate / "machines" / "bystar3015.json", ec))
        return std::filesystem::weakly_canonical(candidate, ec).string();
  }
  return CUTROUTE_DATA_DIR;
}

}  // namespace

const char* data_dir() {
  static const std::string dir = find_data_dir();
  return dir.c_str();
}

}  // namespace cutroute
