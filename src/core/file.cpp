#include <cutroute/core/file.hpp>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <cutroute/core/diagnostic.hpp>

namespace cutroute {

namespace {

std::string too_large(std::uintmax_t max_bytes) { return "file is larger than " + std::to_string(max_bytes >> 20) + " MB"; }

}  // namespace

Result<std::string> read_file(const std::string& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error("is a directory, not a file", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error("cannot open: " + std::string(std::strerror(errno)), path);
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) {
    // A pipe, FIFO or device has no size: read to its end, but no further than the limit (an
    // endless input such as /dev/zero held 2.8 GB after 4 s).
    in.clear();
    std::string content;
    std::array<char, 1 << 16> buf;
    while (in.read(buf.data(), buf.size()) || in.gcount() > 0) {
      content.append(buf.data(), static_cast<std::size_t>(in.gcount()));
      if (content.size() > max_bytes) return make_error(too_large(max_bytes), path);
    }
    if (in.bad()) return make_error("read error", path);
    return content;
  }
  if (static_cast<std::uintmax_t>(size) > max_bytes) return make_error(too_large(max_bytes), path);
  // Read straight into a string of the file's size: through a stream buffer a 200 MB program was
  // held twice (415 MB resident).
  in.seekg(0, std::ios::beg);
  std::string content(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(content.data(), size)) return make_error("read error", path);
  return content;
}

}  // namespace cutroute
