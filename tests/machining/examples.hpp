// Test helper: the worked-example problems shipped in data/machining/, read through the JSON reader.
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <cutroute/core/version.hpp>
#include <cutroute/machining/problem_json.hpp>

#include "support/paths.hpp"

namespace cutroute::test {

inline std::string machining_example_path(const std::string& file) {
  return std::string(cutroute::data_dir()) + "/machining/" + file;
}

inline machining::Problem load_machining_example(const std::string& file) {
  const std::string path = machining_example_path(file);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  auto r = machining::read_problem_json(ss.str(), path);
  if (!r) throw std::runtime_error(format(r.error()));
  return std::move(r).value();
}

inline const char* kE0 = "boring-E0-gilbert-taylor.json";
inline const char* kE1 = "boring-E1-finish-roughness.json";
inline const char* kE2 = "boring-E2-cored-accuracy.json";
inline const char* kE3 = "boring-E3-rough-power.json";

// |a/b − 1| <= rel, with a readable failure.
#define EXPECT_REL(a, b, rel) EXPECT_NEAR((a) / (b), 1.0, (rel)) << #a " = " << (a) << ", expected " << (b)

// Half a unit in the last printed digit (`decimals` after the point): "compare to the printed precision".
inline double printed(int decimals) { return 0.5 * std::pow(10.0, -decimals) * (1.0 + 1e-9); }

}  // namespace cutroute::test
