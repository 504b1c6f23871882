// The JSON boundary: defaults, and every kind of bad input named by its JSON path.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include <cutroute/core/json_text.hpp>
#include <cutroute/machining/problem_json.hpp>

#include "examples.hpp"

namespace cutroute::machining {
namespace {

using nlohmann::json;

json example_json(const char* file) {
  std::ifstream in(test::machining_example_path(file));
  return json::parse(in);
}

// Reads a mutated example and returns the error message ("" when it was accepted).
std::string error_of(const json& j) {
  auto r = read_problem_json(j.dump(), "mutated.json");
  return r ? std::string() : r.error().message;
}

TEST(MachiningJson, ExamplesReadWithDefaults) {
  json j = example_json(test::kE1);
  j["operation"].erase("l_extra");
  j["operation"].erase("passes");
  j["tool"].erase("kappa_r");
  j["quality"].erase("k_Ra");
  j["accuracy"].erase("P");
  j["accuracy"].erase("integration");
  j["search"].erase("grid");
  j["rates"].erase("rate_map");
  auto r = read_problem_json(j.dump());
  ASSERT_TRUE(r) << r.error().message;
  const Problem& p = *r;
  EXPECT_EQ(p.op.l_extra, 3.0);
  EXPECT_EQ(p.op.passes, 1);
  EXPECT_EQ(p.tool.kappa_r, 90.0);
  EXPECT_EQ(p.quality.k_Ra, 1.0);
  EXPECT_EQ(p.accuracy->P, 0.9973);
  EXPECT_EQ(p.accuracy->n_phi, 36);
  EXPECT_EQ(p.accuracy->n_z, 1);
  EXPECT_EQ(p.accuracy->cubature.m, 64);
  EXPECT_EQ(p.search.grid_vc, 241);
  EXPECT_EQ(p.econ.rate_map, RateMap::physical);
  EXPECT_EQ(p.life.sets.size(), 1u);
  EXPECT_EQ(p.life.sets[0].f_hi, 0.3);
  EXPECT_FALSE(p.life.source.empty());
}

TEST(MachiningJson, DepthFromPreHoleDiameter) {
  json j = example_json(test::kE2);
  j["operation"].erase("ap");
  j["operation"]["D_pre"] = 37.0;
  auto r = read_problem_json(j.dump());
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_DOUBLE_EQ(r->op.ap, 1.5);
}

TEST(MachiningJson, TaylorAndKienzleAndRatioModels) {
  json j = example_json(test::kE2);
  j["tool_life"] = {{"model", "taylor"}, {"C", 500}, {"n", 0.25}};
  j["force"]["tangential"] = {{"model", "kienzle"}, {"kc11", 2220}, {"mc", 0.14}};
  j["force"]["radial"] = {{"model", "ratio"}, {"k_r", 0.4}};
  auto r = read_problem_json(j.dump());
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->life.kind, ToolLifeKind::taylor);
  EXPECT_EQ(r->tangential.kind, ForceKind::kienzle);
  EXPECT_EQ(r->radial->kind, ForceKind::ratio);
}

struct BadCase {
  const char* what;
  void (*mutate)(json&);
  const char* expect1;
  const char* expect2;
};

TEST(MachiningJson, BadInputNamesTheField) {
  const BadCase cases[] = {
      {"missing D", [](json& j) { j["operation"].erase("D"); }, "operation.D", "missing"},
      {"missing section", [](json& j) { j.erase("machine"); }, "machine", "missing"},
      {"negative length", [](json& j) { j["operation"]["L"] = -60; }, "operation.L", "positive"},
      {"negative overrun", [](json& j) { j["operation"]["l_extra"] = -1; }, "operation.l_extra", ">= 0"},
      {"f_min > f_max", [](json& j) { j["search"]["f_min"] = 0.4; }, "search.f_min", "f_max"},
      {"vc_min > vc_max", [](json& j) { j["search"]["vc_min"] = 700; }, "search.vc_min", "vc_max"},
      {"unknown life model", [](json& j) { j["tool_life"]["model"] = "kronenberg"; }, "tool_life.model",
       "unknown model name"},
      {"unknown force model", [](json& j) { j["force"]["radial"]["model"] = "kienzle"; },
       "force.radial.model", "unknown model name"},
      {"unknown overhang mode", [](json& j) { j["accuracy"]["bar"]["overhang_mode"] = "telescopic"; },
       "accuracy.bar.overhang_mode", "unknown model name"},
      {"unknown rate map", [](json& j) { j["rates"]["rate_map"] = "reverse"; }, "rates.rate_map", "unknown"},
      {"typo", [](json& j) { j["tool"]["r_epsilon"] = 0.4; }, "tool.r_epsilon", "unknown field"},
      {"string for number", [](json& j) { j["operation"]["D"] = "40"; }, "operation.D", "expected a number"},
      {"eta > 1", [](json& j) { j["machine"]["eta"] = 1.2; }, "machine.eta", "(0, 1]"},
      // Unit slips: micrometres and watts where the schema wants mm and kW.
      {"r_eps in um", [](json& j) { j["tool"]["r_eps"] = 400; }, "tool.r_eps", "smaller than the bore radius"},
      {"P_motor in W", [](json& j) { j["machine"]["P_motor"] = 7500; }, "machine.P_motor", "at most 1000 kW"},
      {"K_TZ in um", [](json& j) { j["accuracy"]["K_TZ"] = 6; }, "accuracy.K_TZ", "below D/10"},
      {"odd simpson", [](json& j) { j["accuracy"]["integration"]["simpson_m"] = 63; }, "simpson_m", "even"},
      // Found by fuzzing: each within its range, together they ran for minutes (SIGTERM ignored).
      {"cubature too fine",
       [](json& j) {
         j["accuracy"]["integration"] = {{"n_phi", 3600}, {"n_z", 1000}, {"simpson_m", 4096}, {"simpson_n", 4096}};
       },
       "accuracy.integration", "at most 2e8"},
      {"P = 1", [](json& j) { j["accuracy"]["P"] = 1.0; }, "accuracy.P", "(0, 1)"},
      {"bad f_range",
       [](json& j) {
         j["tool_life"]["sets"][0]["f_range"] = {0.3, 0.1};
       },
       "tool_life.sets[0].f_range", "lo < hi"},
      {"grid too small",
       [](json& j) {
         j["search"]["grid"] = {2, 241};
       },
       "search.grid", "[3, 4001]"},
      {"hollow bar wider than bar", [](json& j) { j["accuracy"]["bar"]["d_in"] = 30; }, "accuracy.bar.d_in",
       "[0, d)"},
      {"accuracy without radial force", [](json& j) { j["force"].erase("radial"); }, "force.radial",
       "required"},
      {"passes not integer", [](json& j) { j["operation"]["passes"] = 1.5; }, "operation.passes", "integer"},
      {"depth beyond radius", [](json& j) { j["operation"]["ap"] = 25; }, "operation.ap", "radius"},
      // Found by fuzzing (session 39): a bore of 1e308 mm turned at 0 rpm for an infinite time,
      // reported optimal; a 1e-300 rpm spindle speed rounded the optimum to a cost of 1e302; a
      // 4001 x 4001 grid with 12 sweep values took 47 s.
      {"edge along the feed", [](json& j) { j["tool"]["kappa_r"] = 180; }, "tool.kappa_r", "(0, 180) degrees"},
      {"bore beyond 100 m", [](json& j) { j["operation"]["D"] = 1e308; }, "operation.D", "at most 100000 mm"},
      {"spindle speed below 1 rpm", [](json& j) { j["machine"]["spindle_steps"] = {1e-300, 1000}; }, "machine.spindle_steps[]",
       "at least 1 rpm"},
      {"grid and sweep too large",
       [](json& j) {
         j["search"]["grid"] = {4001, 4001};
         j["accuracy"]["K_TZ_sweep"] = {0.005, 0.01, 0.02};
       },
       "search.grid", "at most 5e+07 grid points"},
  };
  for (const auto& c : cases) {
    json j = example_json(test::kE1);
    c.mutate(j);
    const std::string msg = error_of(j);
    EXPECT_NE(msg.find(c.expect1), std::string::npos) << c.what << ": " << msg;
    EXPECT_NE(msg.find(c.expect2), std::string::npos) << c.what << ": " << msg;
  }
}

// Every missing required field in one message (the reader stops at the first; each is filled with
// a stand-in and the file read again), a missing section with the fields it needs; nothing more
// when only one is missing.
// JSON lets a parser keep either value of a repeated key; nlohmann kept the last without a word,
// and {"D": 40, "D": 400} was solved for D = 400 (session 49 audit).
TEST(MachiningJson, ARepeatedKeyIsAnError) {
  const auto r = read_problem_json(R"({"operation": {"D": 40, "L": 60, "D": 400}})", "dup.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, "dup.json");
  EXPECT_NE(r.error().message.find("key \"D\" appears twice in one object"), std::string::npos) << r.error().message;
  // The same key in two objects is no repeat.
  EXPECT_FALSE(duplicate_json_key(R"({"a": {"D": 1}, "b": {"D": 2}, "c": [{"x": 1}, {"x": 2}]})"));
  EXPECT_EQ(duplicate_json_key(R"({"a": [{"x": 1, "y": 2, "x": 3}]})"), std::optional<std::string>("x"));
}

// nlohmann reports a number beyond double's range as out_of_range, with no position: the message
// named neither file nor line (session 49 audit: "D": 1e999).
TEST(MachiningJson, ANumberOutOfRangeNamesItsLine) {
  const auto r = read_problem_json("{\n  \"operation\": {\n    \"D\": 1e999,\n    \"L\": 60\n  }\n}\n", "big.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, "big.json");
  EXPECT_EQ(r.error().line, std::optional<long>(3));
  EXPECT_EQ(r.error().message, "not valid JSON: number overflow parsing '1e999'");
  // A syntax error keeps its line, without nlohmann's exception tag.
  const auto s = parse_json_text("{\n  \"a\": 1,\n  \"b\": }\n", "s.json");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().line, std::optional<long>(3));
  EXPECT_EQ(s.error().message.rfind("not valid JSON: parse error at line 3", 0), 0U) << s.error().message;
}

TEST(MachiningJson, EveryMissingFieldIsNamedAtOnce) {
  json j = example_json(test::kE1);
  j["operation"].erase("D");
  j["tool"].erase("r_eps");
  j["search"].erase("vc_min");
  auto r = read_problem_json(j.dump(), "three.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "operation.D: missing required field (and 2 more: tool.r_eps, search.vc_min)");
  j = example_json(test::kE1);
  j.erase("operation");
  r = read_problem_json(j.dump(), "section.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message.rfind("operation: missing required field (and ", 0), 0u) << r.error().message;
  EXPECT_NE(r.error().message.find("operation.D"), std::string::npos) << r.error().message;
  j = example_json(test::kE1);
  j["tool"].erase("r_eps");
  r = read_problem_json(j.dump(), "one.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "tool.r_eps: missing required field");
}

TEST(MachiningJson, SyntaxErrorHasALine) {
  std::ifstream in(test::test_data("machining/bad-syntax.json"));
  std::stringstream ss;
  ss << in.rdbuf();
  auto r = read_problem_json(ss.str(), "bad-syntax.json");
  ASSERT_FALSE(r);
  ASSERT_TRUE(r.error().line);
  EXPECT_EQ(*r.error().line, 3);
  EXPECT_EQ(r.error().file, "bad-syntax.json");
  EXPECT_NE(format(r.error()).find("bad-syntax.json:3"), std::string::npos) << format(r.error());
}

TEST(MachiningJson, NotAnObject) {
  auto r = read_problem_json("[1, 2, 3]");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("expected an object"), std::string::npos);
}

}  // namespace
}  // namespace cutroute::machining

namespace cutroute::machining {
namespace {

TEST(MachiningJson, TransitionsForm) {
  std::ifstream in(test::machining_example_path("boring-two-transitions-E2-E1.json"));
  std::stringstream ss;
  ss << in.rdbuf();
  auto t = read_transitions_json(ss.str());
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_TRUE(t->is_list);
  ASSERT_EQ(t->items.size(), 2u);
  EXPECT_DOUBLE_EQ(t->items[0].op.ap, 1.5);
  EXPECT_DOUBLE_EQ(t->items[1].econ.t_load, 0.0);
  // A single problem reads as one transition.
  auto one = read_transitions_json(example_json(test::kE1).dump());
  ASSERT_TRUE(one);
  EXPECT_FALSE(one->is_list);
  EXPECT_EQ(one->items.size(), 1u);
  // Errors carry the transition's index in the path.
  nlohmann::json j = nlohmann::json::parse(ss.str());
  j["transitions"][1]["operation"].erase("D");
  auto bad = read_transitions_json(j.dump());
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("transitions[1].operation.D"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(read_transitions_json(R"({"transitions": []})"));
}

}  // namespace
}  // namespace cutroute::machining
