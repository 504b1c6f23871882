// `cutroute speed` and `cutroute estimate` end to end: JSON field names, exit codes, messages.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/core/version.hpp>
#include <cutroute/cost/machine_profile.hpp>

#include "support/paths.hpp"

namespace cutroute::cost {
namespace {

using nlohmann::json;

// The default machine profile, with its speed table as an absolute path (so that the copy
// written elsewhere still finds it).
json default_profile() {
  std::ifstream in(default_machine_profile_path());
  json j = json::parse(in);
  j["speed_table"] =
      std::filesystem::absolute(std::filesystem::path(default_machine_profile_path()).parent_path() /
                                "../materials/bystar3015.json")
          .string();
  return j;
}

test::CommandOutput cli(const std::string& args) { return test::run_command(test::cli_path() + " " + args); }

json cli_json(const std::string& args) {
  const auto r = cli(args);
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  auto j = json::parse(r.out, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << r.out;
  return j;
}

TEST(CliSpeed, JsonFieldsAndPaperValue) {
  const auto j = cli_json("speed --material AMg3M --thickness 1 --frames 1962 --json");
  for (const char* f : {"v_on_m_s", "v_on_mm_min", "v_set_m_s", "regime", "measured"})
    EXPECT_TRUE(j.contains(f)) << f;
  EXPECT_NEAR(j["v_on_m_s"].get<double>(), 0.04779, 0.000005);
  EXPECT_NEAR(j["v_on_mm_min"].get<double>(), j["v_on_m_s"].get<double>() * 60000.0, 1e-9);
  EXPECT_DOUBLE_EQ(j["v_set_m_s"].get<double>(), 0.1);
  EXPECT_EQ(j["regime"], "power");
  EXPECT_EQ(j["measured"], true);
}

TEST(CliSpeed, TextOutputAndExtrapolatedRow) {
  const auto r = cli("speed --material St10 --thickness 8 --frames 120");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("cubic regime"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("extrapolated"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mm/min"), std::string::npos);
}

TEST(CliSpeed, Errors) {
  auto r = cli("speed --material Copper --thickness 1 --frames 10");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("AMg3M"), std::string::npos) << r.err;
  r = cli("speed --material AMg3M --thickness 4 --frames 10");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1, 1.5, 2, 3, 5"), std::string::npos) << r.err;
  const auto j = cli_json("speed --material AMg3M --thickness 4 --frames 10 --interpolate --json");
  EXPECT_EQ(j["warnings"].size(), 1u);
  r = cli("speed --material AMg3M --thickness 1");  // --frames missing
  EXPECT_EQ(r.exit_code, 1);
}

TEST(CliEstimate, JsonFieldsMatchTheIssue) {
  const auto j = cli_json("estimate " + test::test_data("nc/square_abs_mm.nc") +
                          " --material AMg3M --thickness 1 --json");
  for (const char* f : {"pierces", "cut_length_mm", "rapid_length_mm", "frames", "v_on_set_m_s", "v_on_m_s",
                        "t_cut_const_speed_s", "t_cut_s", "cost", "breakdown"})
    EXPECT_TRUE(j.contains(f)) << f;
  for (const char* f : {"cutting_s", "rapid_s", "pierce_s", "dwell_s"})
    EXPECT_TRUE(j["breakdown"].contains(f)) << f;
  EXPECT_EQ(j["pierces"], 1);
  EXPECT_EQ(j["frames"], 10);
  EXPECT_NEAR(j["cut_length_mm"].get<double>(), 300.0, 1e-9);
  // n = 10 < n0 = 70: the cubic, faster than set
  const double v = -4e-12 * 1000 + 3e-8 * 100 - 9e-5 * 10 + 0.105;
  EXPECT_NEAR(j["v_on_m_s"].get<double>(), v, 1e-15);
  EXPECT_NEAR(j["t_cut_s"].get<double>(), 0.3 / v + std::sqrt(800.0) / 1000.0 / 1.0 + 0.3, 1e-9);
  EXPECT_NEAR(j["t_cut_const_speed_s"].get<double>(), 3.0 + std::sqrt(800.0) / 1000.0 + 0.3, 1e-9);
}

TEST(CliEstimate, DwellInBreakdown) {
  const auto j = cli_json("estimate " + test::test_data("nc/dwell_comments_crlf.nc") + " --json");
  EXPECT_NEAR(j["breakdown"]["dwell_s"].get<double>(), 1.75, 1e-12);
  // The file's one pierce has a programmed 0.5 s dwell: that dwell is its pierce time, so t_pt of
  // eq. 10 is taken out of the total once (not counted twice).
  const double t_pt = j["breakdown"]["pierce_s"].get<double>() / j["pierces"].get<double>();
  EXPECT_NEAR(j["breakdown"]["pierce_replaced_s"].get<double>(), t_pt, 1e-12);
  EXPECT_NEAR(j["breakdown"]["total_s"].get<double>(), j["t_cut_s"].get<double>() + 1.75 - t_pt, 1e-9);
}

TEST(CliEstimate, BrokenProgramExitsTwoWithLine) {
  const std::string f = test::test_data("nc/bad/arc_radius_mismatch.nc");
  const auto r = cli("estimate " + f);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(f + ":4: error: arc end is not on its circle"), std::string::npos) << r.err;
  const auto w = cli("estimate " + test::test_data("nc/cutter_comp_misc.nc"));
  EXPECT_EQ(w.exit_code, 0);
  EXPECT_NE(w.err.find("cutter_comp_misc.nc:14: warning: unknown word G12"), std::string::npos) << w.err;
}

TEST(CliEstimate, MachineProfileOptionAndErrors) {
  json j = default_profile();
  j["rapid_speed_m_s"] = 0.5;
  j["dialect"] = "rs274-m7m9";
  const auto path = (std::filesystem::temp_directory_path() / "cutroute-cli-profile.json").string();
  std::ofstream(path) << j.dump(1);
  const auto e =
      cli_json("estimate " + test::test_data("nc/m7m9_beam.nc") + " --machine " + path + " --json");
  EXPECT_EQ(e["pierces"], 2);
  EXPECT_NEAR(e["breakdown"]["rapid_s"].get<double>(), 0.020 / 0.5, 1e-12);

  j["cutting"][3]["pierce_time_s"] = "long";
  std::ofstream(path) << j.dump(1);
  const auto bad = cli("estimate " + test::test_data("nc/square_abs_mm.nc") + " --machine " + path);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("cutting[3].pierce_time_s must be a number"), std::string::npos) << bad.err;

  j["cutting"][3]["pierce_time_s"] = 1;
  j["dialect"] = "sinumerik";
  std::ofstream(path) << j.dump(1);
  const auto d = cli("estimate " + test::test_data("nc/square_abs_mm.nc") + " --machine " + path);
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("field dialect: unknown dialect 'sinumerik'"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("plasma-thc"), std::string::npos) << d.err;  // the post dialects are listed too
  std::filesystem::remove(path);
}

// A program `optimize --dialect plasma-thc` wrote is read by `estimate --dialect plasma-thc` as it
// was written: the torch-height outputs M64/M65 at every contour are known codes, not warnings.
TEST(CliEstimate, ReadsAProgramWithThePostDialectThatWroteIt) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cutroute-cli-thc-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto prog = (dir / "slots.ngc").string();
  const auto w = cli("optimize " + test::test_data("dxf/slots_random_order.dxf") + " -o " + prog +
                     " --dialect plasma-thc --time-limit 0.2 --quiet");
  ASSERT_EQ(w.exit_code, 0) << w.err;
  std::size_t torch_on = 0;
  {
    std::ifstream in(prog);
    for (std::string line; std::getline(in, line);) torch_on += line.find("M3 S1") != std::string::npos;
  }
  ASSERT_GT(torch_on, 0u);

  const auto r = cli("estimate " + prog + " --dialect plasma-thc --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("unknown word"), std::string::npos) << r.err;
  const auto j = json::parse(r.out);
  EXPECT_EQ(j["dialect"], "plasma-thc");
  EXPECT_EQ(j["pierces"], torch_on);
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"];
  // The same program with the profile's rs274 reader warns about the outputs it does not know.
  const auto plain = cli("estimate " + prog);
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find("unknown word M64 ignored"), std::string::npos) << plain.err;
  // Once per code, not at every contour, and with the dialect that explains them.
  EXPECT_EQ(plain.err.find("unknown word M64", plain.err.find("unknown word M64") + 1), std::string::npos) << plain.err;
  EXPECT_NE(plain.err.find("are what the post dialect 'plasma-thc' writes: --dialect plasma-thc"), std::string::npos) << plain.err;
  // A post dialect given as a JSON file reads the same.
  const auto by_path = cli_json("estimate " + prog + " --dialect " + std::string(data_dir()) +
                                "/dialects/plasma-thc.json --json");
  EXPECT_EQ(by_path["cut_length_mm"], j["cut_length_mm"]);
  // A machine profile names the dialect the same way: by name, or by a file beside the profile.
  json profile = default_profile();
  std::filesystem::copy_file(std::string(data_dir()) + "/dialects/plasma-thc.json", dir / "my-thc.json");
  for (const char* named : {"plasma-thc", "my-thc.json"}) {
    profile["dialect"] = named;
    std::ofstream((dir / "machine.json").string()) << profile.dump(1);
    const auto p = cli("estimate " + prog + " --machine " + (dir / "machine.json").string() + " --json");
    ASSERT_EQ(p.exit_code, 0) << named << ": " << p.err;
    const auto pj = json::parse(p.out);
    EXPECT_EQ(pj["pierces"], torch_on) << named;
    EXPECT_EQ(pj["cut_length_mm"], j["cut_length_mm"]) << named;
    EXPECT_TRUE(pj["warnings"].empty()) << named << ": " << pj["warnings"];
  }

  // optimize writes with the profile's dialect when --dialect is not given, by name or file.
  for (const char* named : {"plasma-thc", "my-thc.json"}) {
    profile["dialect"] = named;
    std::ofstream((dir / "machine.json").string()) << profile.dump(1);
    const auto o = cli("optimize " + test::test_data("dxf/slots_random_order.dxf") + " -o " + (dir / "p2.ngc").string() +
                       " --report " + (dir / "p2.json").string() + " --machine " + (dir / "machine.json").string() +
                       " --time-limit 0.2 --quiet");
    ASSERT_EQ(o.exit_code, 0) << named << ": " << o.err;
    std::ifstream in(dir / "p2.json");
    EXPECT_EQ(json::parse(in)["dialect"], "plasma-thc") << named;
    const auto back = cli_json("estimate " + (dir / "p2.ngc").string() + " --dialect plasma-thc --json");
    EXPECT_TRUE(back["warnings"].empty()) << named << ": " << back["warnings"];
    EXPECT_EQ(back["pierces"], torch_on) << named;
  }
  // A profile whose machine reads other beam codes (M7/M9) or dwells in milliseconds: the generic
  // post would write a program that does not cut there. An error, unless --dialect says how to write.
  for (const char* reader : {"rs274-m7m9", "fanuc-ms"}) {
    profile["dialect"] = reader;
    std::ofstream((dir / "machine.json").string()) << profile.dump(1);
    const std::string base = "optimize " + test::test_data("dxf/slots_random_order.dxf") + " -o " + (dir / "p3.ngc").string() +
                             " --machine " + (dir / "machine.json").string() + " --time-limit 0.2 --quiet";
    std::filesystem::remove(dir / "p3.ngc");
    const auto refused = cli(base);
    EXPECT_EQ(refused.exit_code, 2) << reader;
    EXPECT_NE(refused.err.find("machine.json: error: the machine profile's dialect '" + std::string(reader) + "'"), std::string::npos)
        << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "p3.ngc"));
    EXPECT_EQ(cli(base + " --dialect generic").exit_code, 0) << reader;
  }

  const auto bad = cli("estimate " + prog + " --dialect nosuch");
  EXPECT_EQ(bad.exit_code, 2);
  for (const char* listed : {"unknown --dialect 'nosuch'", "rs274-m7m9", "fanuc-ms", "generic", "plasma-thc"})
    EXPECT_NE(bad.err.find(listed), std::string::npos) << listed << ": " << bad.err;
  std::filesystem::remove_all(dir);
}

// Found auditing `estimate`: its JSON warnings were text only, without the code every other
// warning of the tool carries, and the hint naming the post dialect that wrote a program reached
// stderr only. `diagnostics` has them as optimize's report does, each with its code.
TEST(CliEstimate, JsonDiagnosticsCarryCodes) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-cli-codes-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto prog = (dir / "thc.ngc").string();
  std::ofstream(prog) << "G21 G90\nG0 X10 Y0\nM3 S1\nM64 P0\nG1 X20 F1000\nM65 P0\nM5\nG0 X0 Y0 A1\nM2\n";
  const auto j = cli_json("estimate " + prog + " --material St10kp --thickness 3.5 --json");
  ASSERT_TRUE(j.contains("diagnostics")) << j.dump(1);
  std::vector<std::string> codes;
  for (const auto& d : j["diagnostics"]) {
    EXPECT_EQ(d.value("severity", ""), "warning") << d;
    codes.push_back(d.value("code", ""));
  }
  const std::vector<std::string> expected = {"material.conditions", "gcode.unknown_m_code", "gcode.unknown_m_code",
                                             "gcode.unknown_word", "gcode.post_dialect"};
  EXPECT_EQ(codes, expected) << j["diagnostics"].dump(1);
  EXPECT_EQ(j["diagnostics"][1]["line"], 4);
  // `warnings` keeps its text, one entry per diagnostic, the hint now included.
  ASSERT_EQ(j["warnings"].size(), expected.size());
  EXPECT_NE(j["warnings"][4].get<std::string>().find("post dialect 'plasma-thc'"), std::string::npos) << j["warnings"];
  // Warnings beyond the reader's cap are counted there too.
  std::string many = "G21\n";
  for (int i = 0; i < 60; ++i) many += "G0 X1 A1\n";
  std::ofstream((dir / "many.ngc").string()) << many << "M2\n";
  const auto m = cli_json("estimate " + (dir / "many.ngc").string() + " --json");
  ASSERT_FALSE(m["diagnostics"].empty());
  EXPECT_EQ(m["diagnostics"].back().value("code", ""), "gcode.warnings_capped");
  EXPECT_NE(m["diagnostics"].back().value("message", "").find("10 more warning(s) not shown"), std::string::npos)
      << m["diagnostics"].back();
  std::filesystem::remove_all(dir);
}

// A copied binary reads the data/ folder beside it (a shop's deployment), not the source tree it
// was built from; CUTROUTE_DATA_DIR overrides both, and a missing profile names the folder.
TEST(CliData, ACopiedBinaryReadsTheDataBesideIt) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-copied-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(test::cli_path(), dir / "cutroute");
  std::filesystem::copy(data_dir(), dir / "data", std::filesystem::copy_options::recursive);
  json profile = json::parse(std::ifstream(dir / "data" / "machines" / "bystar3015.json"));
  profile["name"] = "the copy's own machine";
  std::ofstream(dir / "data" / "machines" / "bystar3015.json") << profile.dump(1);
  const std::string exe = (dir / "cutroute").string();
  const auto r = test::run_command("'" + exe + "' estimate " + test::test_data("nc/square_abs_mm.nc") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["machine"], "the copy's own machine");
  const auto missing = test::run_command("CUTROUTE_DATA_DIR=" + (dir / "nowhere").string() + " '" + exe + "' estimate " +
                                         test::test_data("nc/square_abs_mm.nc"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("the built-in machine profile, in the data folder " + (dir / "nowhere").string()), std::string::npos)
      << missing.err;
  std::filesystem::remove_all(dir);
}

// Post dialects a shop writes: Fanuc-style millisecond dwells, a park move in the footer, inch
// coordinates to 3 decimals. Each program's report is what `estimate` reads from it with the same
// dialect; the park move is in the quote, the inch arcs stay arcs, and no line passes LinuxCNC's
// 255 characters even under a long file name.
TEST(CliEstimate, ShopDialectsAreQuotedAsEstimateReadsThem) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-dialects-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string dxf = (dir / (std::string(230, 'n') + ".dxf")).string();
  ASSERT_EQ(cli("demo " + dxf).exit_code, 0);
  const std::pair<const char*, const char*> dialects[] = {
      {"plain", R"({"name": "plain"})"},
      {"ms", R"({"pierce": ["G4 P{pierce_ms}"]})"},
      {"park", R"({"footer": ["G0 X0 Y1200"]})"},
      {"in3", R"({"units": "in", "decimals": 3})"},
  };
  std::map<std::string, json> report;
  std::map<std::string, std::string> program;
  for (const auto& [name, text] : dialects) {
    const std::string dialect = (dir / (std::string(name) + ".json")).string(), prog = (dir / (std::string(name) + ".ngc")).string(),
                      rep = (dir / (std::string(name) + ".rep.json")).string();
    std::ofstream(dialect) << text;
    const auto r = cli("optimize " + dxf + " -o " + prog + " --report " + rep + " --dialect " + dialect +
                       " --technique standard --kerf-mode none --time-limit 0 --work-limit 1 --threads 1");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << name << ": " << r.err;
    report[name] = json::parse(std::ifstream(rep));
    std::ifstream in(prog);
    program[name].assign(std::istreambuf_iterator<char>(in), {});
    const auto back = cli_json("estimate " + prog + " --dialect " + dialect + " --json");
    for (const char* key : {"pierces", "cut_length_mm", "rapid_length_mm", "frames", "t_cut_s", "total_s"}) {
      const double want = report[name][key].get<double>();
      const double got = key == std::string("total_s") ? back["breakdown"]["total_s"].get<double>() : back[key].get<double>();
      EXPECT_NEAR(got, want, 1e-6 * std::max(1.0, want)) << name << " " << key;
    }
    std::istringstream lines(program[name]);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 255u) << name << ": " << line.substr(0, 60);
  }
  // 18 pierces of 0.3 s (AMg3M 1 mm) written as G4 P300, quoted as 0.3 s each, as the plain dialect.
  EXPECT_NE(program["ms"].find("G4 P300\n"), std::string::npos);
  EXPECT_NEAR(report["ms"]["total_s"].get<double>(), report["plain"]["total_s"].get<double>(), 1e-9);
  // The park move: the rapid back from the last cut to (0, 1200) instead of the origin, quoted.
  EXPECT_GT(report["park"]["rapid_length_mm"].get<double>(), report["plain"]["rapid_length_mm"].get<double>() + 500);
  EXPECT_GT(report["park"]["t_cut_s"].get<double>(), report["plain"]["t_cut_s"].get<double>());
  // As many arcs in inches to 0.001 in as in millimetres to 1 µm (they were cut into chords).
  auto arcs = [](const std::string& p) {
    std::size_t n = 0;
    for (std::size_t at = p.find("\nG"); at != std::string::npos; at = p.find("\nG", at + 1)) n += p[at + 2] == '2' || p[at + 2] == '3';
    return n;
  };
  EXPECT_GT(arcs(program["plain"]), 10u);
  EXPECT_EQ(arcs(program["in3"]), arcs(program["plain"]));
  EXPECT_EQ(report["in3"]["frames"], report["plain"]["frames"]);
  std::filesystem::remove_all(dir);
}

// optimize --start: the report's first rapid comes from that point, and estimate measures it from
// the same point when told (the program itself cannot say where the head stands).
TEST(CliEstimate, StartPointAsOptimizeUsedIt) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-start-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string dxf = (dir / "d.dxf").string(), prog = (dir / "p.ngc").string(), rep = (dir / "r.json").string();
  ASSERT_EQ(cli("demo " + dxf).exit_code, 0);
  ASSERT_EQ(cli("optimize " + dxf + " -o " + prog + " --report " + rep + " --start 2000,1000 --quiet").exit_code, 0);
  const json r = json::parse(std::ifstream(rep));
  const auto at = cli_json("estimate " + prog + " --start 2000,1000 --json");
  EXPECT_NEAR(at["rapid_length_mm"].get<double>(), r["rapid_length_mm"].get<double>(), 1e-6);
  EXPECT_NEAR(at["t_cut_s"].get<double>(), r["t_cut_s"].get<double>(), 1e-9);
  EXPECT_NEAR(at["breakdown"]["total_s"].get<double>(), r["total_s"].get<double>(), 1e-9);
  // The report's breakdown is the same object as the estimate's, key for key.
  ASSERT_EQ(r["breakdown"].size(), at["breakdown"].size());
  for (const auto& [key, value] : at["breakdown"].items()) {
    ASSERT_TRUE(r["breakdown"].contains(key)) << key;
    EXPECT_NEAR(r["breakdown"][key].get<double>(), value.get<double>(), 1e-9) << key;
  }
  // The program-level fields an integrator reads from either output have the same names and values.
  for (const char* key : {"pierces", "cut_length_mm", "frames", "v_on_set_m_s", "v_on_m_s", "v_on_regime", "measured_speed_row",
                          "t_cut_const_speed_s", "cost", "cost_unit", "material", "thickness_mm"}) {
    ASSERT_TRUE(at.contains(key)) << key;
    ASSERT_TRUE(r.contains(key)) << key;
    if (at[key].is_number_float()) EXPECT_NEAR(at[key].get<double>(), r[key].get<double>(), 1e-6) << key;
    else EXPECT_EQ(at[key], r[key]) << key;
  }
  // From the origin the first rapid is longer.
  EXPECT_GT(cli_json("estimate " + prog + " --json")["rapid_length_mm"].get<double>(), r["rapid_length_mm"].get<double>() + 100);
  EXPECT_EQ(cli("estimate " + prog + " --start 1,x").exit_code, 1);
  // A thickness alone is the profile's default material, as with optimize.
  const auto t = cli_json("estimate " + prog + " --thickness 1.5 --json");
  EXPECT_EQ(t["material"], "AMg3M");
  EXPECT_EQ(t["thickness_mm"], 1.5);
  std::filesystem::remove_all(dir);
}

TEST(CliEstimate, MaterialAndThicknessGoTogether) {
  EXPECT_EQ(cli("estimate " + test::test_data("nc/square_abs_mm.nc") + " --material AMg3M").exit_code, 1);
  const auto r =
      cli("estimate " + test::test_data("nc/square_abs_mm.nc") + " --material AMg3M --thickness 7");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no row for AMg3M 7 mm"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cutroute::cost

namespace cutroute::cost {
namespace {

TEST(CliEstimate, MotionModelWhenTheProfileHasAcceleration) {
  json j = default_profile();
  j["motion"] = {{"accel_m_s2", 1.0}, {"junction_deviation_mm", 0.0}, {"block_time_s", 0.0}};
  const auto path = (std::filesystem::temp_directory_path() / "cutroute-cli-motion.json").string();
  std::ofstream(path) << j.dump(1);
  // square_abs_mm.nc: 100, 50, 100, 50 mm at F6000 (100 mm/s), stopping at each 90° corner
  // (no deviation allowed) with a = 1000 mm/s^2: each side L/v + v/a.
  const auto e =
      cli_json("estimate " + test::test_data("nc/square_abs_mm.nc") + " --machine " + path + " --json");
  ASSERT_TRUE(e.contains("motion"));
  EXPECT_NEAR(e["motion"]["cutting_s"].get<double>(), 2 * (1.0 + 0.1) + 2 * (0.5 + 0.1), 1e-9);
  EXPECT_NEAR(e["motion"]["mean_cut_speed_m_s"].get<double>(), 0.3 / 3.4, 1e-12);
  const auto plain = cli_json("estimate " + test::test_data("nc/square_abs_mm.nc") + " --json");
  EXPECT_FALSE(plain.contains("motion"));
  std::filesystem::remove(path);
}

// Found by fuzzing (session 39): reading a FIFO nobody writes to blocks in open(), and Ctrl-C
// only asked the run to stop; the process could be ended by SIGKILL alone. For a command that
// stops on request (optimize, gtsp) the first SIGINT still asks for a graceful stop (the process
// lives on), the second ends it; estimate, which cannot stop gracefully, ends at the first
// (tests/cli/signals_test.cpp).
TEST(CliSignals, ASecondInterruptEndsARunThatCannotStop) {
  const auto dir = std::filesystem::temp_directory_path() / ("cutroute-fifo-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto fifo = dir / "blocked.dxf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // As a script file: written inline, the shell popen runs would expand $! and $p itself. The run's
  // output goes to /dev/null, so that a run that outlived the script cannot hold the pipe open.
  const auto script = dir / "interrupt.sh";
  std::ofstream(script) << "'" << test::cli_path() << "' optimize '" << fifo.string() << "' -o '" << (dir / "blocked.ngc").string()
                        << "' >/dev/null 2>&1 &\n"
                        << "p=$!\nsleep 1\nkill -INT $p\nsleep 0.5\nkill -0 $p 2>/dev/null && echo alive\n"
                        << "kill -INT $p\nwait $p\necho exit=$?\n";
  const auto r = test::run_command("timeout -k 2 20 sh '" + script.string() + "'");
  EXPECT_NE(r.out.find("alive"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("exit=130"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cutroute::cost
