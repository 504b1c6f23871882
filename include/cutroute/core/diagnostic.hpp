// Diagnostics: what went wrong (or looks wrong) in an input, with file, line, entity and layer.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cutroute {

enum class Severity { info, warning, error };

const char* to_string(Severity s);

struct Diagnostic {
  Severity severity = Severity::error;
  std::string message;
  std::string file;                 // input file path; empty when not from a file
  std::optional<long> line;         // 1-based line in `file`
  std::string handle;               // DXF entity handle (hex string), empty when unknown
  std::string layer;                // DXF layer, empty when unknown
  // Stable machine-readable kind for integrators and policies, e.g. "nest.crossing",
  // "nest.common_edge", "nest.touch", "nest.no_area", "chain.open"; empty when none applies.
  std::string code;
};

// "file:line: error: message (entity 1A, layer 0)" — one line, for stderr.
std::string format(const Diagnostic& d);

Diagnostic make_error(std::string message, std::string file = {}, std::optional<long> line = {});
Diagnostic make_warning(std::string message, std::string file = {}, std::optional<long> line = {});

using Diagnostics = std::vector<Diagnostic>;

bool has_errors(const Diagnostics& ds);

}  // namespace cutroute
