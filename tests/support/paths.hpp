// Paths tests need: our test data, the shared corpus beside the repository, the built CLI.
#pragma once

#include <string>

namespace cutroute::test {

// tests/data/<rel>
inline std::string test_data(const std::string& rel) { return std::string(CUTROUTE_TEST_DATA_DIR) + "/" + rel; }
// ../shared/<rel> (the DXF corpus, GTSPLIB, SOP instances)
inline std::string shared(const std::string& rel) { return std::string(CUTROUTE_SHARED_DIR) + "/" + rel; }
// The cutroute executable of this build.
inline std::string cli_path() { return CUTROUTE_CLI_PATH; }

// Runs a shell command, returns its exit status and what it printed on stdout (stderr kept apart).
struct CommandOutput {
  int exit_code = -1;
  std::string out;
  std::string err;
};
CommandOutput run_command(const std::string& command);
// LinuxCNC's interpreter on a program file (`rs274 -g`), with a HOME of its own: safe to run in parallel.
// With a tool diameter, the program runs with that tool (the kerf) loaded, so G41/G42 really offset
// the path and the interpreter's gouge checks of cutter compensation apply.
CommandOutput run_rs274(const std::string& program, double tool_diameter_mm = 0.0);

}  // namespace cutroute::test
