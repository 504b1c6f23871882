#include <cutroute/core/diagnostic.hpp>

#include <algorithm>

#include <cutroute/core/text.hpp>

namespace cutroute {

const char* to_string(Severity s) {
  switch (s) {
    case Severity::info: return "info";
    case Severity::warning: return "warning";
    case Severity::error: return "error";
  }
  return "error";
}

std::string format(const Diagnostic& d) {
  std::string out;
  if (!d.file.empty()) {
    out += d.file;
    // Appended piecewise: `":" + std::to_string(...)` trips GCC 12's false -Wrestrict at -O3.
    if (d.line) {
      out += ':';
      out += std::to_string(*d.line);
    }
    out += ": ";
  } else if (d.line) {
    out += "line ";
    out += std::to_string(*d.line);
    out += ": ";
  }
  out += to_string(d.severity);
  out += ": ";
  out += d.message;
  // What the message names already (a nest message describes its contour) is not repeated.
  const bool handle = !d.handle.empty() && d.message.find("entity " + d.handle) == std::string::npos;
  const bool layer = !d.layer.empty() && d.message.find("layer " + d.layer) == std::string::npos;
  if (handle || layer) {
    out += " (";
    if (handle) out += "entity " + d.handle;
    if (handle && layer) out += ", ";
    if (layer) out += "layer " + d.layer;
    out += ")";
  }
  return out;
}

// Messages quote input (a DXF value, a G-code line) that may not be UTF-8; reports and pictures need it.
Diagnostic make_error(std::string message, std::string file, std::optional<long> line) {
  return Diagnostic{Severity::error, to_utf8(message), std::move(file), line, {}, {}, {}};
}

Diagnostic make_warning(std::string message, std::string file, std::optional<long> line) {
  return Diagnostic{Severity::warning, to_utf8(message), std::move(file), line, {}, {}, {}};
}

bool has_errors(const Diagnostics& ds) {
  return std::any_of(ds.begin(), ds.end(), [](const Diagnostic& d) { return d.severity == Severity::error; });
}

}  // namespace cutroute
