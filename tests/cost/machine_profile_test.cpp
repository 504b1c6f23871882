// Machine profiles: the shipped default and invalid variants, each error naming its field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include <cutroute/cost/machine_profile.hpp>
#include <cutroute/cost/speed_table.hpp>

namespace cutroute::cost {
namespace {

using nlohmann::json;

json default_json() {
  std::ifstream in(default_machine_profile_path());
  return json::parse(in);
}

TEST(MachineProfile, DefaultLoadsAndCoversEveryTableRow) {
  auto p = load_machine_profile(default_machine_profile_path());
  ASSERT_TRUE(p.ok()) << format(p.error());
  EXPECT_GT(p->rapid_speed_m_s, 0.0);
  EXPECT_EQ(p->dialect.name, "rs274");
  EXPECT_FALSE(p->costs.has_value());  // time form of eq. 3
  ASSERT_TRUE(p->default_material.has_value());
  EXPECT_TRUE(std::filesystem::exists(p->speed_table)) << p->speed_table;
  auto t = load_speed_table(p->speed_table);
  ASSERT_TRUE(t.ok());
  for (const auto& r : t->rows) {
    bool found = false;
    for (const auto& c : p->cutting) {
      auto m = t->resolve_material(c.material);
      found = found || (m.ok() && *m == r.material && c.thickness_mm == r.thickness_mm);
    }
    EXPECT_TRUE(found) << r.material << " " << r.thickness_mm;
  }
}

struct Mutation {
  const char* name;
  std::function<void(json&)> apply;
  const char* expect;  // part of the error message
};

TEST(MachineProfile, InvalidProfilesNameTheField) {
  const Mutation cases[] = {
      {"no_rapid", [](json& j) { j.erase("rapid_speed_m_s"); }, "field rapid_speed_m_s is missing"},
      {"zero_rapid", [](json& j) { j["rapid_speed_m_s"] = 0; }, "field rapid_speed_m_s must be > 0"},
      {"text_rapid", [](json& j) { j["rapid_speed_m_s"] = "fast"; },
       "field rapid_speed_m_s must be a number"},
      {"misspelt", [](json& j) { j["rapid_speed"] = 1; }, "unknown field rapid_speed"},
      {"neg_pierce", [](json& j) { j["cutting"][2]["pierce_time_s"] = -1; },
       "field cutting[2].pierce_time_s must be >= 0"},
      {"no_kerf", [](json& j) { j["cutting"][0].erase("kerf_mm"); }, "field cutting[0].kerf_mm is missing"},
      {"bad_cut_key", [](json& j) { j["cutting"][1]["speed"] = 1; }, "unknown field cutting[1].speed"},
      {"no_cutting", [](json& j) { j["cutting"] = json::array(); },
       "field cutting must be a non-empty array"},
      {"neg_head", [](json& j) { j["head_lift_lower_s"] = -0.1; }, "field head_lift_lower_s must be >= 0"},
      {"dialect_code",
       [](json& j) {
         j["dialect"] = {{"name", "x"}, {"beam_on", {"X3"}}, {"beam_off", {"M5"}}};
       },
       "field dialect.beam_on[0] must be an M code"},
      {"dialect_half",
       [](json& j) {
         j["dialect"] = {{"name", "x"}, {"beam_on", {"M3"}}};
       },
       "dialect.beam_on and dialect.beam_off must be given together"},
      {"dialect_unit",
       [](json& j) {
         j["dialect"] = {{"name", "rs274"}, {"dwell_p_unit", "min"}};
       },
       "field dialect.dwell_p_unit"},
      {"costs_half",
       [](json& j) {
         j["costs"] = {{"unit", "EUR"}, {"c_on_per_m", 1}, {"c_off_per_m", 0.1}};
       },
       "field costs.c_pt is missing"},
      {"motion_neg", [](json& j) { j["motion"]["accel_m_s2"] = -2; }, "field motion.accel_m_s2 must be > 0"},
      {"v_set_neg", [](json& j) { j["cutting"][0]["v_set_m_s"] = -0.1; },
       "field cutting[0].v_set_m_s must be > 0"},
      {"job_thickness", [](json& j) { j["default_job"]["thickness_mm"] = 0; },
       "field default_job.thickness_mm must be > 0"},
      {"no_table", [](json& j) { j.erase("speed_table"); }, "field speed_table is missing"},
      // Found by fuzzing (session 39): each overflowed the estimate (a NaN or 4e300-s total, exit 0).
      {"huge_pierce", [](json& j) { j["cutting"][2]["pierce_time_s"] = 1e308; },
       "field cutting[2].pierce_time_s must be at most 3600, got 1e+308"},
      {"huge_head", [](json& j) { j["head_lift_lower_s"] = 1e308; }, "field head_lift_lower_s must be at most 3600"},
      {"creeping_rapid", [](json& j) { j["rapid_speed_m_s"] = 1e-300; }, "field rapid_speed_m_s must be at least 0.001"},
      {"work_area_one", [](json& j) { j["work_area_mm"] = {3000}; }, "field work_area_mm must be two numbers"},
      {"work_area_zero", [](json& j) { j["work_area_mm"] = {0, 1500}; }, "field work_area_mm must hold two lengths"},
  };
  for (const auto& c : cases) {
    json j = default_json();
    c.apply(j);
    const auto path =
        (std::filesystem::temp_directory_path() / (std::string("cutroute-profile-") + c.name + ".json"))
            .string();
    std::ofstream(path) << j.dump(1);
    auto p = load_machine_profile(path);
    ASSERT_FALSE(p.ok()) << c.name;
    EXPECT_EQ(p.error().file, path) << c.name;
    EXPECT_NE(p.error().message.find(c.expect), std::string::npos) << c.name << ": " << p.error().message;
    std::filesystem::remove(path);
  }
}

TEST(MachineProfile, CustomDialectAndCostsAreRead) {
  json j = default_json();
  j["dialect"] = {{"name", "plasma"}, {"beam_on", {"M7"}}, {"beam_off", {"M9"}}, {"dwell_p_unit", "ms"}};
  j["costs"] = {{"unit", "EUR"}, {"c_on_per_m", 0.5}, {"c_off_per_m", 0.01}, {"c_pt", 0.02}};
  j["speed_table"] = default_speed_table_path();  // absolute paths stay as they are
  const auto path = (std::filesystem::temp_directory_path() / "cutroute-profile-custom.json").string();
  std::ofstream(path) << j.dump(1);
  auto p = load_machine_profile(path);
  ASSERT_TRUE(p.ok()) << format(p.error());
  EXPECT_EQ(p->dialect.beam_on, std::vector<int>{7});
  EXPECT_EQ(p->dialect.beam_off, std::vector<int>{9});
  EXPECT_EQ(p->dialect.dwell_p_unit, "ms");
  ASSERT_TRUE(p->costs.has_value());
  EXPECT_DOUBLE_EQ(p->costs->c_on_per_m, 0.5);
  EXPECT_EQ(p->speed_table, default_speed_table_path());
  std::filesystem::remove(path);
}

TEST(MachineProfile, MissingFileAndBadJson) {
  auto a = load_machine_profile("/nonexistent/profile.json");
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().message.find("cannot open"), std::string::npos);
  const auto path = (std::filesystem::temp_directory_path() / "cutroute-profile-broken.json").string();
  std::ofstream(path) << "{\"name\": ";
  auto b = load_machine_profile(path);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().message.find("not valid JSON"), std::string::npos);
  EXPECT_EQ(b.error().line, std::optional<long>(1));
  std::ofstream(path) << "{\"name\": \"a\",\n \"rapid_speed_m_s\": 1e400}";
  auto big = load_machine_profile(path);
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.error().line, std::optional<long>(2)) << format(big.error());
  std::ofstream(path) << R"({"name": "a", "rapid_speed_m_s": 1.0, "rapid_speed_m_s": 100.0})";
  auto c = load_machine_profile(path);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("key \"rapid_speed_m_s\" appears twice in one object"), std::string::npos) << c.error().message;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cutroute::cost
