// Typed access to JSON fields that names the field (a.b[2].c) in every error message.
#pragma once

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include <cutroute/core/file.hpp>
#include <cutroute/core/json_text.hpp>

#include <cutroute/core/result.hpp>

namespace cutroute::cost::detail {

using nlohmann::json;

inline std::string field(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
inline std::string item(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Parses a file; the error names the file and, for syntax errors, the line.
inline Result<json> parse_json_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return make_error("is a directory, not a JSON file", path);
  const auto read = read_file(path);
  if (!read) return read.error();
  const std::string& text = *read;
  auto parsed = parse_json_text(text, path);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (const auto key = duplicate_json_key(text)) return make_error("key \"" + *key + "\" appears twice in one object", path);
  if (!j.is_object()) return make_error("the top level must be a JSON object", path);
  return j;
}

// A finite number at obj[key]; `required` false returns `fallback` when absent or null.
inline Result<double> number(const json& obj, const std::string& key, const std::string& path,
                             bool required = true, double fallback = 0.0) {
  const auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) {
    if (required) return make_error("field " + field(path, key) + " is missing");
    return fallback;
  }
  if (!it->is_number()) return make_error("field " + field(path, key) + " must be a number");
  const double v = it->get<double>();
  if (!std::isfinite(v)) return make_error("field " + field(path, key) + " must be finite");
  return v;
}

// `least`, `most`: the range a machine can have; beyond it a value is a typo or a unit slip, and
// overflowed the estimate (a pierce of 1e308 s made the total NaN).
inline Result<double> in_range(Result<double> v, const std::string& name, double least, double most) {
  if (!v) return v;
  auto text = [](double x) {
    std::ostringstream o;
    o << x;
    return o.str();
  };
  if (*v < least) return make_error("field " + name + " must be at least " + text(least) + ", got " + text(*v));
  if (*v > most) return make_error("field " + name + " must be at most " + text(most) + ", got " + text(*v));
  return v;
}

inline Result<double> positive(const json& obj, const std::string& key, const std::string& path,
                               bool required = true, double fallback = 0.0,
                               double most = std::numeric_limits<double>::infinity()) {
  auto v = number(obj, key, path, required, fallback);
  if (!v) return v;
  if (*v <= 0.0 && (required || obj.contains(key)))
    return make_error("field " + field(path, key) + " must be > 0");
  return in_range(v, field(path, key), -std::numeric_limits<double>::infinity(), most);
}

inline Result<double> non_negative(const json& obj, const std::string& key, const std::string& path,
                                   bool required = true, double fallback = 0.0,
                                   double most = std::numeric_limits<double>::infinity()) {
  auto v = number(obj, key, path, required, fallback);
  if (!v) return v;
  if (*v < 0.0) return make_error("field " + field(path, key) + " must be >= 0");
  return in_range(v, field(path, key), 0.0, most);
}

inline Result<std::string> string(const json& obj, const std::string& key, const std::string& path,
                                  bool required = true, const std::string& fallback = {}) {
  const auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) {
    if (required) return make_error("field " + field(path, key) + " is missing");
    return fallback;
  }
  if (!it->is_string()) return make_error("field " + field(path, key) + " must be a string");
  return it->get<std::string>();
}

inline Result<bool> boolean(const json& obj, const std::string& key, const std::string& path,
                            bool required = true, bool fallback = false) {
  const auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) {
    if (required) return make_error("field " + field(path, key) + " is missing");
    return fallback;
  }
  if (!it->is_boolean()) return make_error("field " + field(path, key) + " must be true or false");
  return it->get<bool>();
}

// Attaches the file name to an error that names a field.
inline Diagnostic in_file(Diagnostic d, const std::string& file) {
  if (d.file.empty()) d.file = file;
  return d;
}

}  // namespace cutroute::cost::detail
