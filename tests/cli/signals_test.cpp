// How runs stop on SIGINT and SIGTERM: exit codes, what is written, what is left behind.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include <cutroute/io/output_file.hpp>

#include "support/files.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;

// The temporary files of outputs (".cutroute-<pid>-<n>.tmp") left in a folder.
int stray_temp_files(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().starts_with(".cutroute-") ? 1 : 0;
  return n;
}

// Runs a shell script written to a file (inline, popen's shell would expand $! and $p itself),
// bounded so that a run that does not stop cannot hang the suite.
CommandOutput run_script(const fs::path& dir, const std::string& text) {
  const auto script = dir / "run.sh";
  std::ofstream(script) << text;
  return run_command("timeout -k 2 120 sh '" + script.string() + "'");
}

// Found auditing how runs stop: a second Ctrl-C while the outputs were being written ended the
// process with their temporary files (tens of MB on big nests) left beside them. Here the report
// is a FIFO nobody reads: the run blocks writing it, the program and picture already in their
// temporary files, and only the second Ctrl-C can end it.
TEST(CliSignals, ASecondInterruptWhileWritingLeavesNoTemporaryFile) {
  const auto dir = fresh_temp_dir("signals", "tmp-left");
  const auto dxf = dir / "demo.dxf", fifo = dir / "report.json";
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf.string()).exit_code, 0);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::ostringstream script;
  script << "'" << cli_path() << "' optimize '" << dxf.string() << "' -o '" << (dir / "demo.ngc").string() << "' --svg '"
         << (dir / "demo.svg").string() << "' --report '" << fifo.string() << "' --quiet >/dev/null 2>&1 &\np=$!\n"
         // Until a temporary file has content: the outputs are being written.
         << "for i in $(seq 600); do [ -n \"$(find '" << dir.string()
         << "' -name '.cutroute-*' -size +0)\" ] && break; sleep 0.1; done\n"
         << "kill -INT $p\nsleep 0.3\nkill -INT $p\nwait $p\necho exit=$?\n";
  const auto r = run_script(dir, script.str());
  EXPECT_NE(r.out.find("exit=130"), std::string::npos) << r.out;
  EXPECT_EQ(stray_temp_files(dir), 0);
  EXPECT_FALSE(fs::exists(dir / "demo.ngc"));  // all outputs or none: the report never came
  fs::remove_all(dir);
}

// Found reviewing how runs stop: a second Ctrl-C while an output set was being renamed into place
// ended the process between two renames, leaving a new program beside the old run's report. The
// handler now leaves such a signal to the renames, which raise it once the set is in place.
TEST(CliSignalsDeathTest, ASecondSignalWaitsForTheOutputsToBeInPlace) {
  EXPECT_EXIT(
      {
        {
          const io::CommitGuard commit;
          if (!io::defer_signal_while_committing(SIGUSR1)) std::_Exit(3);
          std::fputs("renamed\n", stderr);
        }
        std::_Exit(4);  // not reached: the signal is raised as the guard ends
      },
      testing::KilledBySignal(SIGUSR1), "renamed");
  EXPECT_FALSE(io::defer_signal_while_committing(SIGUSR1));  // no renames under way: the handler's own
}

// A command that never looks at the stop request (estimate, machining, inspect) ends at the first
// SIGTERM: a supervisor's or `timeout`'s single signal went unheeded, the run went on to its end.
TEST(CliSignals, ACommandThatCannotStopEndsAtTheFirstSignal) {
  const auto dir = fresh_temp_dir("signals", "first");
  const auto fifo = dir / "blocked.ngc";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::ostringstream script;
  script << "'" << cli_path() << "' estimate '" << fifo.string() << "' >/dev/null 2>&1 &\np=$!\nsleep 1\nkill -TERM $p\nsleep 1\n"
         << "kill -0 $p 2>/dev/null && echo alive\nkill -KILL $p 2>/dev/null\nwait $p\necho exit=$?\n";
  const auto r = run_script(dir, script.str());
  EXPECT_EQ(r.out.find("alive"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("exit=143"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

// Found auditing how runs stop: gtsp stopped by Ctrl-C printed its route with the status a time
// limit gives (feasible) and nothing else: a benchmark table took it for a full run's.
TEST(CliSignals, AnInterruptedGtspRunSaysSo) {
  const auto dir = fresh_temp_dir("signals", "gtsp");
  std::ostringstream script;
  script << "'" << cli_path() << "' gtsp '" << shared("data/sop/prob.100.sop") << "' --time-limit 60 --json 2>'"
         << (dir / "err.txt").string() << "' &\np=$!\nsleep 1\nkill -INT $p\nwait $p\necho exit=$?\n";
  const auto r = run_script(dir, script.str());
  EXPECT_NE(r.out.find("exit=0"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
  EXPECT_EQ(j.value("interrupted", false), true) << r.out;
  EXPECT_FALSE(j["tour"].empty());
  EXPECT_NE(read_text(dir / "err.txt").find("warning: the run was interrupted (Ctrl-C, SIGTERM or a closed terminal)"), std::string::npos);
  fs::remove_all(dir);
}

// A closed terminal (SIGHUP) ended a run at once, with no program written; it now stops the run as
// SIGTERM does. Started under nohup, the run keeps ignoring it and goes on to its time limit.
TEST(CliSignals, AClosedTerminalStopsTheRunUnlessNohup) {
  const auto dir = fresh_temp_dir("signals", "hup");
  for (const bool nohup : {false, true}) {
    std::ostringstream script;
    script << (nohup ? "nohup '" : "'") << cli_path() << "' gtsp '" << shared("data/sop/prob.100.sop") << "' --time-limit "
           << (nohup ? "3" : "60") << " --json >'" << (dir / "out.txt").string() << "' 2>/dev/null &\np=$!\nsleep 1\n"
           << "kill -HUP $p\nwait $p\necho exit=$?\n";
    const auto r = run_script(dir, script.str());
    EXPECT_NE(r.out.find("exit=0"), std::string::npos) << nohup << ' ' << r.out;
    const std::string out = read_text(dir / "out.txt");
    ASSERT_FALSE(out.empty()) << nohup;
    const auto j = nlohmann::json::parse(out.substr(0, out.find('\n')));
    EXPECT_EQ(j.value("interrupted", false), !nohup) << out;
    if (nohup) {
      EXPECT_GE(j["time_s"].get<double>(), 2.9);
    }
  }
  fs::remove_all(dir);
}

// Found auditing how runs stop: a batch stopped before every sheet was begun exited 2, the code of
// a bad input, and its summary called the sheets not begun errors. The sheets are FIFOs, one more
// than the batch's workers (one per core), so that one is never begun: SIGTERM comes while the
// others wait for their drawing.
TEST(CliSignals, AStoppedBatchExitsWithTheSignalAndNamesTheSheetsNotStarted) {
  const auto dir = fresh_temp_dir("signals", "batch");
  const auto dxf = dir / "demo.dxf";
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf.string()).exit_code, 0);
  const unsigned sheets = std::max(1u, std::thread::hardware_concurrency()) + 1;
  std::ostringstream nests, feed;
  for (unsigned i = 0; i < sheets; ++i) {
    const auto fifo = dir / ("sheet" + std::to_string(i) + ".dxf");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    nests << " '" << fifo.string() << "'";
    // Each writer gives up after a while: the sheet never begun never opens its FIFO.
    feed << "timeout 20 sh -c \"cat '" << dxf.string() << "' > '" << fifo.string() << "'\" >/dev/null 2>&1 &\nw=\"$w $!\"\n";
  }
  const auto out = dir / "out";
  std::ostringstream script;
  script << "'" << cli_path() << "' optimize" << nests.str() << " -o '" << out.string() << "' --quiet 2>'"
         << (dir / "err.txt").string() << "' &\np=$!\nsleep 1\nkill -TERM $p\nsleep 0.3\n" << feed.str()
         << "wait $p\necho exit=$?\nkill $w 2>/dev/null\n";
  const auto r = run_script(dir, script.str());
  EXPECT_NE(r.out.find("exit=143"), std::string::npos) << r.out << read_text(dir / "err.txt");
  const std::string summary = read_text(out / "summary.csv");
  EXPECT_NE(summary.find(".dxf,not started,"), std::string::npos) << summary;
  EXPECT_EQ(summary.find(".dxf,error,"), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(out / "sheet0.ngc"));  // begun before the signal: its best program
  fs::remove_all(dir);
}

// Found auditing how runs stop: the progress line was written whole, and a line as wide as the
// terminal wraps, so each rewrite ("\r") left a row behind; the end cleared only 79 columns. Run
// in a pseudo-terminal of 40 columns (script(1), util-linux), every rewrite must fit in 39.
TEST(CliProgress, TheLineFitsTheTerminal) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) missing";
  const auto dir = fresh_temp_dir("signals", "a_folder_with_a_name_longer_than_the_terminal_is_wide");
  const auto dxf = dir / "a_sheet_with_a_long_name.dxf";
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf.string()).exit_code, 0);
  std::ostringstream inner;
  inner << "stty cols 40; '" << cli_path() << "' optimize '" << dxf.string() << "' -o '" << (dir / "p.ngc").string()
        << "' --time-limit 1";
  std::ostringstream command;
  command << "timeout 60 script -qfc \"" << inner.str() << "\" /dev/null";
  const auto r = run_command(command.str());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The terminal ends lines with "\r\n"; within a line, every piece ended by "\r" is one rewrite of
  // the progress line, the last piece the results printed once it was cleared.
  std::string out = r.out;
  for (std::size_t k; (k = out.find("\r\n")) != std::string::npos;) out.erase(k, 1);
  for (std::size_t k; (k = out.find("\x1b[K")) != std::string::npos;) out.erase(k, 3);
  int lines = 0;
  std::istringstream rows(out);
  for (std::string row; std::getline(rows, row);) {
    for (std::size_t from = 0, to; (to = row.find('\r', from)) != std::string::npos; from = to + 1) {
      const std::string piece = row.substr(from, to - from);
      if (piece.empty()) continue;
      ++lines;
      EXPECT_LE(piece.size(), 39U) << piece;
    }
  }
  EXPECT_GT(lines, 0) << r.out;  // the progress line was shown
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test
