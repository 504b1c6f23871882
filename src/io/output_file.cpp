#include <cutroute/io/output_file.hpp>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace cutroute::io {

namespace {

// A fresh temporary name next to `path`.
std::string temp_name(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

Status refuse_folder(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error("cannot write output: is a folder", path);
  return Ok{};
}

// Writes the whole content to `tmp`; on failure nothing is left there.
Status write_temp(const std::string& tmp, const std::string& path, std::string_view content) {
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out) return make_error("cannot write output: " + std::string(std::strerror(errno)), path);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  if (!out) {
    out.close();
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    return make_error("writing output failed (disk full?)", path);
  }
  return Ok{};
}

Status move_into_place(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() overwrites ec ("Success")
    std::filesystem::remove(tmp, ec);
    return make_error("cannot move the finished output into place: " + why, path);
  }
  return Ok{};
}

void to_stdout(std::string_view content) {
  std::cout.write(content.data(), static_cast<std::streamsize>(content.size()));
  std::cout.flush();
}

}  // namespace

Status write_files_atomic(const std::vector<OutputFile>& files) {
  for (const auto& f : files)
    if (f.path != "-")
      if (Status st = refuse_folder(f.path); !st) return st;
  std::vector<std::string> tmps(files.size());
  auto drop = [&](std::size_t from) {
    std::error_code ec;
    for (std::size_t k = from; k < files.size(); ++k)
      if (!tmps[k].empty()) std::filesystem::remove(tmps[k], ec);
  };
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (files[k].path == "-") continue;
    const std::string tmp = temp_name(files[k].path);
    if (Status st = write_temp(tmp, files[k].path, files[k].content); !st) {
      drop(0);
      return st;
    }
    tmps[k] = tmp;
  }
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (tmps[k].empty()) continue;
    if (Status st = move_into_place(tmps[k], files[k].path); !st) {
      drop(k + 1);
      return st;
    }
  }
  for (const auto& f : files)
    if (f.path == "-") to_stdout(f.content);
  return Ok{};
}

Status write_file_atomic(const std::string& path, std::string_view content) {
  return write_files_atomic({{path, std::string(content)}});
}

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

}  // namespace cutroute::io
