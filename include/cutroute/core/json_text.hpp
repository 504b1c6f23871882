// Reading JSON input texts: syntax errors with the line they are on, and keys written twice.
#pragma once

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/core/diagnostic.hpp>
#include <cutroute/core/result.hpp>

namespace cutroute {

// JSON leaves a repeated key to the parser, and nlohmann keeps the last value without a word: a
// machining problem with "D": 40 and later "D": 400 was solved for 400. Input files are read
// through this first, so that the repeat is an error naming the key. nullopt: no repeat (or text
// that is not JSON, which the caller's parse reports).
inline std::optional<std::string> duplicate_json_key(std::string_view text) {
  std::vector<std::set<std::string>> open;
  std::optional<std::string> found;
  const nlohmann::json::parser_callback_t watch = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) {
      open.emplace_back();
    } else if (event == Event::object_end) {
      if (!open.empty()) open.pop_back();
    } else if (event == Event::key && !open.empty() && !found && parsed.is_string()) {
      if (!open.back().insert(parsed.get<std::string>()).second) found = parsed.get<std::string>();
    }
    return true;
  };
  [[maybe_unused]] const nlohmann::json whole = nlohmann::json::parse(text.begin(), text.end(), watch, false);
  return found;
}

// The text parsed, or "not valid JSON: ..." naming `file` and the line. nlohmann reports a number
// out of double's range (1e999) as out_of_range without a position, and its messages open with an
// exception tag a shop has no use for; the line is then the first one holding the literal.
inline Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file) {
  auto line_at = [&](std::size_t byte) {
    const std::size_t upto = std::min(byte, text.size());
    return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(upto), '\n'));
  };
  auto untagged = [](std::string what) {
    if (!what.empty() && what.front() == '[') {
      const auto close = what.find("] ");
      if (close != std::string::npos) what.erase(0, close + 2);
    }
    return what;
  };
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    return make_error("not valid JSON: " + untagged(e.what()), file, line_at(e.byte));
  } catch (const nlohmann::json::exception& e) {
    std::string what = untagged(e.what());
    std::optional<long> line;
    const auto q1 = what.find('\''), q2 = what.rfind('\'');
    if (q1 != std::string::npos && q2 > q1 + 1) {
      const auto at = text.find(what.substr(q1 + 1, q2 - q1 - 1));
      if (at != std::string_view::npos) line = line_at(at);
    }
    return make_error("not valid JSON: " + what, file, line);
  }
}

}  // namespace cutroute
