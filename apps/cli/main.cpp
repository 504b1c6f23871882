// cutroute: the command-line entry point. Parses options, runs one subcommand, maps to exit codes.
#include <unistd.h>

#include <csignal>
#include <iostream>

#include <cutroute/core/stop.hpp>
#include <cutroute/core/version.hpp>
#include <cutroute/io/output_file.hpp>

#include "commands.hpp"

namespace cutroute::cli {

int fail(const Diagnostic& d) {
  std::cerr << "cutroute: " << format(d) << '\n';
  return kInputError;
}

std::string json_text(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool show_progress(bool quiet) { return !quiet && ::isatty(STDERR_FILENO); }

}  // namespace cutroute::cli

namespace {
// The first Ctrl-C (or SIGTERM, SIGHUP) asks the run to stop and write its best result; the second ends the
// process at once, for whatever cannot stop: a read blocked on a FIFO nobody writes to, a step
// that does not look at the stop request. A command that never looks at it (estimate, machining,
// inspect) ends at the first: a supervisor's single SIGTERM went unheeded. Ending, the process
// leaves no temporary file of an output it was writing.
volatile std::sig_atomic_t signal_seen = 0;     // the first signal's number, 0 before any
volatile std::sig_atomic_t stops_on_request = 0;  // the running command looks at the stop request
extern "C" void on_signal(int sig) {
  if (signal_seen != 0 || stops_on_request == 0) {
    if (cutroute::io::defer_signal_while_committing(sig)) return;  // ends once the outputs are in place
    cutroute::io::remove_temp_files();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  signal_seen = sig;
  cutroute::StopToken::global().request_stop();
}
}  // namespace

int cutroute::cli::interrupt_signal() { return signal_seen; }

int main(int argc, char** argv) {
  using namespace cutroute::cli;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // A closed terminal stops a run as SIGTERM does (it ended it with no program written), unless the
  // run was started to ignore it (nohup).
  if (std::signal(SIGHUP, on_signal) == SIG_IGN) std::signal(SIGHUP, SIG_IGN);

  CLI::App app{"cutroute: cutting-route optimizer and CAM engine for CNC sheet cutting", "cutroute"};
  app.set_version_flag("--version", std::string("cutroute ") + cutroute::version());
  app.require_subcommand(1);
  Commands commands;
  add_optimize(app, commands);
  add_inspect(app, commands);
  add_demo(app, commands);
  add_speed(app, commands);
  add_estimate(app, commands);
  add_gtsp(app, commands);
  add_machining(app, commands);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsageError;
  }
  for (const auto& c : commands) {
    if (c.app->parsed()) {
      stops_on_request = c.stops_on_request ? 1 : 0;
      try {
        return c.run();
      } catch (const std::bad_alloc&) {
        std::cerr << "cutroute: error: out of memory\n";
        return kInputError;
      } catch (const std::exception& e) {
        std::cerr << "cutroute: error: " << e.what() << '\n';
        return kInputError;
      }
    }
  }
  return kUsageError;
}
