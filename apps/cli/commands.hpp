// The CLI's subcommands: each cmd_*.cpp registers one and returns its exit code when run.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cutroute/core/diagnostic.hpp>

namespace cutroute::cli {

// Exit codes shared by every subcommand. A batch that Ctrl-C or SIGTERM stopped before every
// sheet was cut exits 128 + the signal's number (130, 143), as a shell reports a process a signal
// ended: its sheets were not wrong, only not done.
enum ExitCode : int { kOk = 0, kUsageError = 1, kInputError = 2, kSignalBase = 128 };

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
  // The command reads StopToken::global() and writes its best result when asked to stop; the
  // others end at the first SIGINT or SIGTERM (main.cpp).
  bool stops_on_request = false;
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
// The signal (SIGINT, SIGTERM) that asked the run to stop, 0 while none has.
int interrupt_signal();
// True when stderr is a terminal and --quiet was not given: progress may be shown.
bool show_progress(bool quiet);

}  // namespace cutroute::cli
