// End-to-end tests of the cutroute executable: exit codes, messages, outputs.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/files.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  auto d = fs::temp_directory_path() / ("cutroute-cli-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Cli, VersionAndHelp) {
  auto r = run_command(cli_path() + " --version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("cutroute "), std::string::npos);
  r = run_command(cli_path() + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("inspect"), std::string::npos);
}

TEST(Cli, UsageErrorsExitOne) {
  EXPECT_EQ(run_command(cli_path()).exit_code, 1);
  EXPECT_EQ(run_command(cli_path() + " no-such-command").exit_code, 1);
  EXPECT_EQ(run_command(cli_path() + " inspect").exit_code, 1);  // missing NEST
  auto r = run_command(cli_path() + " inspect x.dxf --sheet abc");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--sheet"), std::string::npos);
}

// Found by fuzzing: each of these ran with exit 0 (a program ending "G0 Xinf", the default thickness
// for NaN, the default material for "").
TEST(Cli, AbsurdOptionValuesAreUsageErrors) {
  for (const char* bad : {"--start 1e308,0", "--start 0,2e6", "--thickness nan", "--thickness inf", "--material ''"}) {
    auto r = run_command(cli_path() + " optimize /nonexistent/nest.dxf " + bad);
    EXPECT_EQ(r.exit_code, 1) << bad << ": " << r.err;
    EXPECT_NE(r.err.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << bad << ": " << r.err;
  }
}

// `demo -o FILE` writes what `demo FILE` writes, as every other command takes its output after -o.
TEST(Cli, DemoTakesItsOutputAfterDashO) {
  const auto dir = temp_dir("demo-o");
  ASSERT_EQ(run_command(cli_path() + " demo " + (dir / "a.dxf").string()).exit_code, 0);
  ASSERT_EQ(run_command(cli_path() + " demo -o " + (dir / "b.dxf").string()).exit_code, 0);
  const auto text = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_FALSE(text(dir / "a.dxf").empty());
  EXPECT_EQ(text(dir / "a.dxf"), text(dir / "b.dxf"));
  EXPECT_NE(run_command(cli_path() + " demo").exit_code, 0);
}

// A program that cannot be written (its path is a folder) is refused with the reason, and the
// run leaves none of its other outputs: no report or picture of a program that does not exist.
TEST(Cli, OutputOntoADirectoryNamesTheReasonAndLeavesNothing) {
  const auto dir = temp_dir("ontodir");
  ASSERT_EQ(run_command(cli_path() + " demo " + (dir / "n.dxf").string()).exit_code, 0);
  fs::create_directories(dir / "p.ngc");
  auto r = run_command(cli_path() + " optimize " + (dir / "n.dxf").string() + " --time-limit 0.2 -o " + (dir / "p.ngc").string() +
                       " --report " + (dir / "r.json").string() + " --svg " + (dir / "r.svg").string() + " --html " +
                       (dir / "r.html").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("p.ngc: error: cannot write output: is a folder"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
  for (const char* left : {"r.json", "r.svg", "r.html"}) EXPECT_FALSE(fs::exists(dir / left)) << left;
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  // A report that cannot be written leaves no program.
  r = run_command(cli_path() + " optimize " + (dir / "n.dxf").string() + " --time-limit 0.2 -o " + (dir / "q.ngc").string() +
                  " --report " + (dir / "no" / "r.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot write output"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "q.ngc"));
  fs::remove_all(dir);
}

// An output path that is a symbolic link keeps the link (its target gets the program); one that is
// a FIFO (or a device: `-o /dev/null` as root) is written in place, never replaced by a file.
TEST(Cli, OutputsThroughLinksAndPipesKeepThem) {
  const auto dir = temp_dir("links");
  const std::string nest = (dir / "n.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + nest).exit_code, 0);
  fs::create_symlink(dir / "target.ngc", dir / "link.ngc");  // dangling until written
  // A work budget, not a time limit: the two runs must write the same program.
  auto r = run_command(cli_path() + " optimize " + nest + " -o " + (dir / "link.ngc").string() + " --time-limit 0 --work-limit 1 --threads 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir / "link.ngc"));
  const std::string program = read_text(dir / "target.ngc");
  EXPECT_EQ(program.rfind("(cutroute n.dxf)", 0), 0u) << program.substr(0, 40);
  ASSERT_EQ(::mkfifo((dir / "pipe.ngc").c_str(), 0600), 0);
  // Both ends time out rather than hang the suite when the other never opens the FIFO.
  r = run_command("timeout 60 cat " + (dir / "pipe.ngc").string() + " > " + (dir / "got.ngc").string() + " & timeout 60 " +
                  cli_path() + " optimize " + nest + " -o " + (dir / "pipe.ngc").string() +
                  " --time-limit 0 --work-limit 1 --threads 1 -q; code=$?; wait; exit $code");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_fifo(dir / "pipe.ngc"));
  EXPECT_EQ(read_text(dir / "got.ngc"), program);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  fs::remove_all(dir);
}

// Two outputs into one file (or both to stdout) are refused before any work; with the program on
// stdout the summary line goes to stderr, out of the program's stream.
TEST(Cli, OutputsShareNoFileAndStdoutCarriesOnlyTheProgram) {
  const auto dir = temp_dir("same");
  const std::string nest = (dir / "n.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + nest).exit_code, 0);
  auto r = run_command("cd " + dir.string() + " && " + cli_path() + " optimize n.dxf -o same.out --report ./same.out --time-limit 0.2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-o and --report name the same output"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "same.out"));
  r = run_command(cli_path() + " optimize " + nest + " -o - --html - --time-limit 0.2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-o and --html name the same output"), std::string::npos) << r.err;
  r = run_command(cli_path() + " optimize " + nest + " -o - --time-limit 0.2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("(cutroute n.dxf)", 0), 0u);
  EXPECT_EQ(r.out.substr(r.out.size() - 4), "M30\n");
  EXPECT_NE(r.err.find(" pierces, cut "), std::string::npos) << r.err;
  // A program that cannot be written to stdout (a full disk behind the pipe) fails the run.
  if (fs::exists("/dev/full")) {
    r = run_command(cli_path() + " optimize " + nest + " -o - --time-limit 0.2 -q > /dev/full");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("writing the output to standard output failed"), std::string::npos) << r.err;
  }
  fs::remove_all(dir);
}

// An output that names the drawing being read (itself, another spelling of its path, a symbolic or
// a hard link to it) is refused before any work, and the drawing stays as it was.
TEST(Cli, AnOutputNeverReplacesItsInput) {
  const auto dir = temp_dir("input");
  const std::string nest = (dir / "n.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + nest).exit_code, 0);
  const std::string drawing = read_text(nest);
  fs::create_symlink("n.dxf", dir / "soft.ngc");
  fs::create_hard_link(nest, dir / "hard.ngc");
  const std::string d = dir.string() + "/";
  for (const std::string& outputs : {"-o " + nest, "-o " + d + "./n.dxf", "-o " + d + "p.ngc --report " + d + "../" +
                                    dir.filename().string() + "/n.dxf", "-o " + d + "p.ngc --svg " + nest,
                                    "-o " + d + "p.ngc --html " + nest, "-o " + d + "soft.ngc", "-o " + d + "hard.ngc",
                                    "-o - --report " + nest}) {
    const auto r = run_command(cli_path() + " optimize " + nest + " " + outputs + " --time-limit 0.2 -q");
    EXPECT_EQ(r.exit_code, 1) << outputs;
    EXPECT_NE(r.err.find("is the input drawing"), std::string::npos) << outputs << ": " << r.err;
    EXPECT_EQ(read_text(nest), drawing) << outputs;
  }
  const auto r = run_command(cli_path() + " inspect " + nest + " --svg " + nest);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(read_text(nest), drawing);
  EXPECT_FALSE(fs::exists(dir / "p.ngc"));
  fs::remove_all(dir);
}

// A batch's output folder that cannot be made is said with its own reason, before any work.
TEST(Cli, BatchFolderThatCannotBeMadeIsSaid) {
  const auto dir = temp_dir("no-folder");
  const std::string nest = (dir / "n.dxf").string();
  ASSERT_EQ(run_command(cli_path() + " demo " + nest).exit_code, 0);
  std::ofstream(dir / "file") << "not a folder";
  const auto r = run_command(cli_path() + " optimize " + nest + " " + nest + " -o " + (dir / "file" / "out").string() + " -q");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot make the output folder: Not a directory"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// What the drawing hides on screen (a layer turned off, an invisible entity) or shows tilted is
// cut, and every run says so on stderr, not only in the report.
TEST(Cli, CurvesTheDrawingHidesAreSaidOnEveryRun) {
  const auto dir = temp_dir("hidden");
  std::ofstream(dir / "h.dxf")
      << "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n0\nLAYER\n2\nOLD\n70\n0\n62\n-1\n0\nENDTAB\n0\nENDSEC\n"
         "0\nSECTION\n2\nENTITIES\n"
         "0\nCIRCLE\n8\n0\n10\n0\n20\n0\n40\n5\n"
         "0\nCIRCLE\n8\nOLD\n10\n30\n20\n0\n40\n5\n"
         "0\nCIRCLE\n8\n0\n60\n1\n10\n60\n20\n0\n40\n5\n"
         "0\nCIRCLE\n8\n0\n10\n90\n20\n0\n30\n0\n40\n5\n210\n0.6\n220\n0\n230\n0.8\n"
         "0\nENDSEC\n0\nEOF\n";
  const auto r = run_command(cli_path() + " optimize " + (dir / "h.dxf").string() + " -o " + (dir / "h.ngc").string() +
                             " --time-limit 0.5 --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* said : {"a layer off in the drawing", "--ignore-layers OLD", "marked invisible",
                           "lies in a plane tilted from the XY plane"})
    EXPECT_NE(r.err.find(said), std::string::npos) << said << "\n" << r.err;
}

TEST(Cli, MissingFileIsAnInputErrorNamingTheFile) {
  auto r = run_command(cli_path() + " inspect /nonexistent/nest.dxf");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/nest.dxf"), std::string::npos) << r.err;
}

TEST(Cli, DemoThenInspectDescribesThePaperLikeSheet) {
  const auto dir = temp_dir("demo");
  const auto dxf = dir / "demo.dxf";
  const auto svg = dir / "demo.svg";
  auto r = run_command(cli_path() + " demo " + dxf.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_command(cli_path() + " inspect " + dxf.string() + " --json --svg " + svg.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["parts"], 14);
  EXPECT_EQ(j["holes"], 7);
  EXPECT_EQ(j["contours_closed"], 22);  // 21 cut contours + the sheet border
  EXPECT_EQ(j["contours_open"], 0);
  EXPECT_EQ(j["max_depth"], 1);
  ASSERT_FALSE(j["sheet"].is_null());
  EXPECT_EQ(j["units_in_file"], "mm");
  EXPECT_EQ(j["layers"].size(), 2u) << j["layers"];  // the demo's CUT and SHEET layers, with their entities
  EXPECT_EQ(j["dropped"]["duplicate_contours"], 0);
  // Analytic cut length: plates (rounded rectangle r15 + Ø80 hole), flanges Ø300 with Ø100 bore,
  // L-brackets 250 x 300 with an R20 inner fillet.
  const double pi = 3.14159265358979323846;
  const double plate = 2 * (400 + 250) - 8 * 15 + 2 * pi * 15 + 2 * pi * 40;
  const double flange = 2 * pi * 150 + 2 * pi * 50;
  const double bracket = 2 * (250 + 300) - 2 * 20 + pi * 20 / 2;
  EXPECT_NEAR(j["cut_length_mm"].get<double>(), 4 * plate + 3 * flange + 7 * bracket, 1e-6);
  EXPECT_NEAR(j["total_length_mm"].get<double>(), 4 * plate + 3 * flange + 7 * bracket + 6000, 1e-6);
  const auto bbox = j["bbox_mm"];
  EXPECT_NEAR(bbox[0].get<double>(), 0, 1e-9);
  EXPECT_NEAR(bbox[2].get<double>(), 2000, 1e-9);
  EXPECT_NEAR(bbox[3].get<double>(), 1000, 1e-9);

  const std::string picture = slurp(svg);
  EXPECT_EQ(picture.rfind("<?xml", 0), 0u);
  EXPECT_NE(picture.find("</svg>"), std::string::npos);
  EXPECT_NE(picture.find("fill-rule=\"evenodd\""), std::string::npos);

  // Same input, same bytes.
  const auto svg2 = dir / "demo2.svg";
  auto r2 = run_command(cli_path() + " inspect " + dxf.string() + " --json --svg " + svg2.string());
  EXPECT_EQ(r2.out, r.out);
  EXPECT_EQ(slurp(svg2), picture);
  fs::remove_all(dir);
}

// Progress on a terminal only (script(1), bsdutils, gives the command one): a line per nest
// rewritten in place, cleared before the summary; none with --quiet or into a pipe.
TEST(Cli, OptimizeShowsProgressOnATerminalOnly) {
  ASSERT_EQ(std::system("command -v script >/dev/null 2>&1"), 0) << "script(1) (bsdutils) is missing";
  const auto dir = temp_dir("progress");
  const auto dxf = dir / "demo.dxf";
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf.string()).exit_code, 0);
  const std::string cmd = cli_path() + " optimize " + dxf.string() + " -o " + (dir / "demo.ngc").string() + " --time-limit 1";
  std::string line = dxf.string() + ": ";
  line.insert(line.begin(), '\r');
  const auto tty = run_command("script -qec '" + cmd + "' /dev/null");
  ASSERT_EQ(tty.exit_code, 0) << tty.out << tty.err;
  EXPECT_NE(tty.out.find(line), std::string::npos) << tty.out;
  const auto quiet = run_command("script -qec '" + cmd + " --quiet' /dev/null");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.out << quiet.err;
  EXPECT_EQ(quiet.out.find(line), std::string::npos) << quiet.out;
  const auto pipe = run_command(cmd);
  ASSERT_EQ(pipe.exit_code, 0) << pipe.err;
  EXPECT_EQ(pipe.err.find('\r'), std::string::npos) << pipe.err;
  fs::remove_all(dir);
}

TEST(Cli, FailedRunLeavesNoOutputBehind) {
  const auto dir = temp_dir("fail");
  const auto svg = dir / "never.svg";
  auto r = run_command(cli_path() + " inspect /nonexistent.dxf --svg " + svg.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(svg));
  for (const auto& e : fs::directory_iterator(dir)) ADD_FAILURE() << "left behind: " << e.path();
  fs::remove_all(dir);
}

// A drawing through a pipe or FIFO (no size to seek to) was refused with "cannot read file".
TEST(Cli, ADrawingIsReadThroughAPipe) {
  const auto dir = temp_dir("pipe");
  const auto dxf = dir / "demo.dxf";
  ASSERT_EQ(run_command(cli_path() + " demo " + dxf.string()).exit_code, 0);
  const auto r = run_command("cat '" + dxf.string() + "' | " + cli_path() + " inspect /dev/stdin");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("entities: CIRCLE 10 LWPOLYLINE 12"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::test
