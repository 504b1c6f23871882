#include "support/files.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>

namespace cutroute::test {

std::filesystem::path fresh_temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("cutroute-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::filesystem::path fresh_temp_dir(const std::string& prefix, const std::string& name) {
  return fresh_temp_dir(prefix + "-" + name);
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace cutroute::test
