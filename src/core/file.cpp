#include <cutroute/core/file.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <cutroute/core/diagnostic.hpp>

namespace cutroute {

Result<std::string> read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error("is a directory, not a file", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error("cannot open: " + std::string(std::strerror(errno)), path);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return make_error("read error", path);
  return ss.str();
}

}  // namespace cutroute
