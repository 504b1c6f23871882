#include "support/paths.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <sstream>

namespace cutroute::test {

CommandOutput run_command(const std::string& command) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const auto err_path = dir / ("cutroute-test-err-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  CommandOutput result;
  const std::string full = command + " 2>" + err_path.string();
  FILE* pipe = ::popen(full.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) result.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream e(err_path);
  std::stringstream ss;
  ss << e.rdbuf();
  result.err = ss.str();
  std::filesystem::remove(err_path);
  return result;
}

CommandOutput run_rs274(const std::string& program) {
  // rs274 truncates and maps $HOME/.tool.mmap: two at once with the same HOME (ctest -j) truncate
  // the file under each other's mapping and die of SIGBUS (exit 135). Each call gets its own HOME.
  static int counter = 0;
  const auto home = std::filesystem::temp_directory_path() /
                    ("cutroute-rs274-home-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(home);
  CommandOutput r = run_command("HOME=" + home.string() + " rs274 -g " + program + " < /dev/null");
  std::filesystem::remove_all(home);
  return r;
}

}  // namespace cutroute::test
