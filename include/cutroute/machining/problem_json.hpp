// Reading a boring problem from JSON (schema: docs/MACHINING-SCHEMA.md), validated at the boundary:
// every error names the JSON path of the field (and the line for syntax errors).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <cutroute/core/result.hpp>
#include <cutroute/machining/problem.hpp>

namespace cutroute::machining {

// Parses, fills defaults, checks every validity rule (validate()). `file` only labels diagnostics.
Result<Problem> read_problem_json(std::string_view text, const std::string& file = {});

// A part with several boring transitions: {"name": ..., "transitions": [problem, ...]} (MACHINING.md
// 3.3: CT sums over transitions). A single problem object reads as one transition. Errors name the
// path inside the transition ("transitions[1].operation.D: ...").
struct Transitions {
  std::string name;
  std::vector<Problem> items;
  bool is_list = false;  // true when the file used the "transitions" form
};
Result<Transitions> read_transitions_json(std::string_view text, const std::string& file = {});

}  // namespace cutroute::machining
