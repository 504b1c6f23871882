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

CommandOutput run_rs274(const std::string& program, double tool_diameter_mm) {
  // rs274 truncates and maps $HOME/.tool.mmap: two at once with the same HOME (ctest -j) truncate
  // the file under each other's mapping and die of SIGBUS (exit 135). Each call gets its own HOME.
  static int counter = 0;
  const auto home = std::filesystem::temp_directory_path() /
                    ("cutroute-rs274-home-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(home);
  std::string command = "HOME=" + home.string() + " rs274 -g " + program + " < /dev/null";
  if (tool_diameter_mm > 0) {
    // Tool 1 with the kerf as its diameter, selected before the program: G41/G42 then offset by
    // half of it. The stand-alone interpreter reads the table in inches (no INI file).
    std::ofstream(home / "kerf.tbl") << "T1 P1 D" << tool_diameter_mm / 25.4 << "\n";
    std::ifstream in(program);
    std::stringstream text;
    text << "T1 M6\n" << in.rdbuf();
    std::ofstream(home / "program.ngc") << text.str();
    command = "HOME=" + home.string() + " rs274 -t " + (home / "kerf.tbl").string() + " -g " + (home / "program.ngc").string() +
              " < /dev/null";
  }
  CommandOutput r = run_command(command);
  std::filesystem::remove_all(home);
  return r;
}

}  // namespace cutroute::test
