// Reading a boring problem from JSON (schema: docs/MACHINING-SCHEMA.md), validated at the boundary:
// every error names the JSON path of the field (and the line for syntax errors).
#pragma once

#include <string>
#include <string_view>

#include <cutroute/core/result.hpp>
#include <cutroute/machining/problem.hpp>

namespace cutroute::machining {

// Parses, fills defaults, checks every validity rule (validate()). `file` only labels diagnostics.
Result<Problem> read_problem_json(std::string_view text, const std::string& file = {});

}  // namespace cutroute::machining
