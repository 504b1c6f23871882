// The CLI's subcommands: each cmd_*.cpp registers one and returns its exit code when run.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cutroute/core/diagnostic.hpp>

namespace cutroute::cli {

// Exit codes shared by every subcommand.
enum ExitCode : int { kOk = 0, kUsageError = 1, kInputError = 2 };

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};
using Commands = std::vector<Command>;

void add_inspect(CLI::App& root, Commands& out);
void add_demo(CLI::App& root, Commands& out);
void add_speed(CLI::App& root, Commands& out);
void add_estimate(CLI::App& root, Commands& out);
void add_gtsp(CLI::App& root, Commands& out);
void add_machining(CLI::App& root, Commands& out);
void add_optimize(CLI::App& root, Commands& out);

// Prints "cutroute: <diagnostic>" to stderr and returns kInputError.
int fail(const Diagnostic& d);
// JSON text of a report (indent < 0: one line). Strings that are not UTF-8 (a file name in a
// legacy encoding) come out with U+FFFD instead of making the dump throw.
std::string json_text(const nlohmann::json& j, int indent = 2);
// True when stderr is a terminal and --quiet was not given: progress may be shown.
bool show_progress(bool quiet);

}  // namespace cutroute::cli
