// duplicate_json_key(): the first key written twice in one object of a JSON text.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

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

}  // namespace cutroute
