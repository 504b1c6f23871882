#include <cutroute/nc/post_dialect.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <set>
#include <type_traits>

#include <nlohmann/json.hpp>

#include <cutroute/core/file.hpp>
#include <cutroute/core/json_text.hpp>
#include <cutroute/core/text.hpp>
#include <cutroute/core/version.hpp>

#include "nc/block_scanner.hpp"

namespace cutroute::nc {
namespace {

using nlohmann::json;

struct FieldError {
  std::string field;
  std::string message;
};

template <class T>
void get(const json& j, const char* key, T& out, std::set<std::string>& seen) {
  seen.insert(key);
  if (!j.contains(key)) return;
  try {
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      // get<int>() would wrap 2147483648 to a negative line number without a word.
      const json& v = j.at(key);
      if (!v.is_number_integer()) throw FieldError{key, "has the wrong type"};
      if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<T>::max())
                                 : v.get<std::int64_t>() < std::numeric_limits<T>::min() ||
                                       v.get<std::int64_t>() > std::numeric_limits<T>::max())
        throw FieldError{key, "is out of range"};
      out = static_cast<T>(v.get<std::int64_t>());
    } else {
      out = j.at(key).get<T>();
    }
  } catch (const json::exception&) {
    throw FieldError{key, "has the wrong type"};
  }
}

// The words of one dialect line, placeholders standing for a number; "" or why it is no block.
std::string words_of(const std::string& written, std::vector<detail::Word>& words) {
  words.clear();
  const std::string line = fill_placeholders(written, "1", "1");
  const auto scan = detail::scan_block(line, [&](const detail::Word& w) { words.push_back(w); });
  return scan.error == detail::ScanError::none ? std::string() : detail::scan_message(scan);
}

bool has_g(const std::vector<detail::Word>& words, double g) {
  return std::any_of(words.begin(), words.end(), [g](const detail::Word& w) { return w.letter == 'G' && std::abs(w.value - g) < 1e-9; });
}

bool has_letter(const std::vector<detail::Word>& words, const std::string& letters) {
  return std::any_of(words.begin(), words.end(), [&](const detail::Word& w) { return letters.find(w.letter) != std::string::npos; });
}

}  // namespace

bool fanuc_dwell(const PostDialect& post) {
  std::vector<detail::Word> words;
  for (const auto* lines : {&post.header, &post.footer, &post.beam_on, &post.pierce, &post.beam_off, &post.thc_on, &post.thc_off})
    for (const std::string& line : *lines) {
      if (line.find("{pierce_ms}") != std::string::npos) return true;
      if (words_of(line, words).empty() && has_g(words, 4) && has_letter(words, "X")) return true;
    }
  return false;
}

namespace {

// What the writer relies on, checked when the file is read, so that a post-processor slip is an
// error naming the field rather than a program that cuts wrongly (LinuxCNC's interpreter, the
// reference, takes at most 255 characters a line: kMaxLine leaves room for the line number).
std::string check_lines(const PostDialect& d) {
  constexpr std::size_t kMaxLine = 200;
  const std::pair<const char*, std::vector<std::string>> fields[] = {
      {"header", d.header},     {"footer", d.footer},           {"program_end", {d.program_end}}, {"beam_on", d.beam_on},
      {"pierce", d.pierce},     {"beam_off", d.beam_off},       {"thc_on", d.thc_on},             {"thc_off", d.thc_off},
      {"kerf_left", {d.kerf_left}}, {"kerf_right", {d.kerf_right}}, {"kerf_off", {d.kerf_off}}};
  std::vector<detail::Word> words;
  bool p_seconds = false;  // a G4 P{pierce_s}: a dwell in seconds, which a Fanuc-style reader misreads
  for (const auto& [field, lines] : fields) {
    const std::string name = std::string("dialect field '") + field + "'";
    for (const std::string& line : lines) {
      const std::string quoted = name + ": line '" + line + "'";
      for (const char c : line)
        if ((static_cast<unsigned char>(c) < 32 && c != '\t') || static_cast<unsigned char>(c) > 126)
          return name + ": a line holds printable ASCII only (one block a line; no line breaks, tabs or accents)";
      if (line.size() > kMaxLine) return name + ": a line is longer than " + std::to_string(kMaxLine) + " characters";
      if (const std::string bad = words_of(line, words); !bad.empty()) return quoted + " is no G-code block: " + bad;
      const bool dwell = has_g(words, 4);
      p_seconds = p_seconds || (dwell && line.find("P{pierce_s}") != std::string::npos);
      const std::string f = field;
      // The writer writes the units word and absolute coordinates with incremental arc centres;
      // a line that changes those moves every later block.
      if ((d.units == "mm" && has_g(words, 20)) || (d.units == "in" && has_g(words, 21)))
        return quoted + " switches to " + (d.units == "mm" ? "inches (G20)" : "millimetres (G21)") +
               " where the dialect's units are " + d.units + ": every coordinate would be read " +
               (d.units == "mm" ? "25.4 times too large" : "25.4 times too small");
      if (has_g(words, 91)) return quoted + " switches to incremental coordinates (G91); the program is written in absolute ones";
      if (has_g(words, 90.1) && d.arc_format == ArcFormat::ij)
        return quoted + " makes arc centres absolute (G90.1); the program writes them incremental (I J)";
      const bool kerf_field = f == "kerf_left" || f == "kerf_right" || f == "kerf_off";
      if (!kerf_field && (has_g(words, 41) || has_g(words, 42) || has_g(words, 41.1) || has_g(words, 42.1)))
        return quoted + " switches cutter compensation on, which only 'kerf_left' and 'kerf_right' may";
      // Beam, pierce, torch-height and kerf lines come between moves of the path: a move there
      // would be cut or travelled unseen (a Z move for the torch is fine).
      // (A Fanuc-style G4 X dwells X seconds.)
      if (f != "header" && f != "footer" && f != "program_end" && has_letter(words, dwell ? "YABCUVWIJR" : "XYABCUVWIJR"))
        return quoted + " moves the head in the plane; only 'header' and 'footer' lines may";
    }
  }
  std::vector<detail::Word> w;
  words_of(d.kerf_left, w);
  if (!has_g(w, 41) && !has_g(w, 41.1)) return "dialect field 'kerf_left' must write G41 (or G41.1): it starts left compensation";
  words_of(d.kerf_right, w);
  if (!has_g(w, 42) && !has_g(w, 42.1)) return "dialect field 'kerf_right' must write G42 (or G42.1): it starts right compensation";
  words_of(d.kerf_off, w);
  if (!has_g(w, 40)) return "dialect field 'kerf_off' must write G40: it ends compensation";
  words_of(d.program_end, w);
  if (!std::any_of(w.begin(), w.end(), [](const detail::Word& x) { return x.letter == 'M' && (x.value == 2 || x.value == 30); }))
    return "dialect field 'program_end' must write M2 or M30: the program has to end";
  if (fanuc_dwell(d) && p_seconds)
    return "dialect writes G4 P{pierce_s} (seconds) beside {pierce_ms} or a G4 X dwell (Fanuc style, where G4 P counts "
           "milliseconds): a reader takes G4 P in one unit";
  return {};
}

}  // namespace

Result<PostDialect> load_post_dialect(const std::string& path) {
  auto text = read_file(path);
  if (!text) return text.error();
  auto parsed = parse_json_text(*text, path);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (const auto key = duplicate_json_key(*text)) return make_error("dialect field '" + *key + "' appears twice", path);
  if (!j.is_object()) return make_error("a dialect file holds one JSON object", path);
  PostDialect d;
  d.file = path;
  d.name = std::filesystem::path(path).stem().string();  // what the report names it, when the file does not
  std::set<std::string> seen;
  std::string arc = "ij", comments = "paren";
  try {
    get(j, "name", d.name, seen);
    get(j, "description", d.description, seen);
    get(j, "units", d.units, seen);
    get(j, "decimals", d.decimals, seen);
    get(j, "feed_decimals", d.feed_decimals, seen);
    get(j, "arc_format", arc, seen);
    get(j, "line_numbers", d.line_numbers, seen);
    get(j, "line_number_start", d.line_number_start, seen);
    get(j, "line_number_step", d.line_number_step, seen);
    get(j, "comments", comments, seen);
    get(j, "header", d.header, seen);
    get(j, "footer", d.footer, seen);
    get(j, "program_end", d.program_end, seen);
    get(j, "beam_on", d.beam_on, seen);
    get(j, "pierce", d.pierce, seen);
    get(j, "beam_off", d.beam_off, seen);
    get(j, "thc_on", d.thc_on, seen);
    get(j, "thc_off", d.thc_off, seen);
    get(j, "kerf_left", d.kerf_left, seen);
    get(j, "kerf_right", d.kerf_right, seen);
    get(j, "kerf_off", d.kerf_off, seen);
    get(j, "outer_clockwise", d.outer_clockwise, seen);
    get(j, "hole_clockwise", d.hole_clockwise, seen);
  } catch (const FieldError& e) {
    return make_error("dialect field '" + e.field + "' " + e.message, path);
  }
  for (const auto& [key, value] : j.items()) {
    if (!seen.count(key)) return make_error("unknown dialect field '" + key + "'", path);
  }
  if (d.units != "mm" && d.units != "in") return make_error("dialect field 'units' must be \"mm\" or \"in\"", path);
  if (arc == "ij") {
    d.arc_format = ArcFormat::ij;
  } else if (arc == "r") {
    d.arc_format = ArcFormat::r;
  } else {
    return make_error("dialect field 'arc_format' must be \"ij\" or \"r\"", path);
  }
  if (comments == "paren") {
    d.comments = CommentStyle::paren;
  } else if (comments == "semicolon") {
    d.comments = CommentStyle::semicolon;
  } else if (comments == "none") {
    d.comments = CommentStyle::none;
  } else {
    return make_error("dialect field 'comments' must be \"paren\", \"semicolon\" or \"none\"", path);
  }
  if (d.decimals < 0 || d.decimals > 6) return make_error("dialect field 'decimals' must be 0..6", path);
  if (d.feed_decimals < 0 || d.feed_decimals > 4) return make_error("dialect field 'feed_decimals' must be 0..4", path);
  if (d.line_number_step <= 0 || d.line_number_step > 100000)
    return make_error("dialect field 'line_number_step' must be 1..100000", path);
  if (d.line_number_start < 0 || d.line_number_start > 99999999)
    return make_error("dialect field 'line_number_start' must be 0..99999999", path);
  if (d.program_end.empty()) return make_error("dialect field 'program_end' must not be empty", path);
  if (const std::string bad = check_lines(d); !bad.empty()) return make_error(bad, path);
  // A dialect cutroute's own reader cannot read back (a beam switched by M30, no M code to start
  // cutting) would give a program whose report and quote are not what it does.
  if (auto reads = reader_dialect(d); !reads) return reads.error();
  return d;
}

Result<PostDialect> find_post_dialect(const std::string& name_or_path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(name_or_path, ec)) return load_post_dialect(name_or_path);
  const std::string builtin = std::string(data_dir()) + "/dialects/" + name_or_path + ".json";
  if (std::filesystem::is_regular_file(builtin, ec)) return load_post_dialect(builtin);
  if (name_or_path.find('/') != std::string::npos || std::filesystem::path(name_or_path).extension() == ".json")
    return make_error("dialect file '" + name_or_path + "' not found (built in: " + join(post_dialect_names(), ", ") + ")");
  return make_error("unknown dialect '" + name_or_path + "' (built in: " + join(post_dialect_names(), ", ") + "; or give a JSON file)");
}

Result<PostDialect> find_post_dialect(const std::string& name_or_path, const std::string& folder) {
  std::error_code ec;
  const std::filesystem::path beside = std::filesystem::path(folder) / name_or_path;
  if (!folder.empty() && std::filesystem::path(name_or_path).is_relative() && std::filesystem::is_regular_file(beside, ec))
    return load_post_dialect(beside.string());
  return find_post_dialect(name_or_path);
}

Result<Dialect> reader_dialect_named(const std::string& name, const std::string& unknown, const std::string& file,
                                     const std::string& folder) {
  if (auto b = builtin_dialect(name)) return b;
  auto post = find_post_dialect(name, folder);
  if (post) return reader_dialect(*post);
  if (!post.error().file.empty()) return post.error();  // a dialect file that does not load
  return make_error(unknown + " '" + name + "' (reader dialects: " + join(builtin_dialect_names(), ", ") +
                        "; post-processor dialects: " + join(post_dialect_names(), ", ") + "; or a dialect JSON file)",
                    file);
}

std::string fill_placeholders(std::string line, const std::string& pierce_s, const std::string& feed, const std::string& pierce_ms) {
  const auto replace = [&line](const std::string& what, const std::string& with) {
    for (auto p = line.find(what); p != std::string::npos; p = line.find(what, p + with.size()))
      line.replace(p, what.size(), with);
  };
  replace("{pierce_s}", pierce_s);
  replace("{pierce_ms}", pierce_ms.empty() ? pierce_s : pierce_ms);
  replace("{feed}", feed);
  return line;
}


bool moves_outside_the_path(const PostDialect& post) {
  std::vector<detail::Word> words;
  for (const auto* lines : {&post.header, &post.footer})
    for (const std::string& line : *lines)
      if (words_of(line, words).empty() && has_letter(words, "XYABCUVWIJR")) return true;
  return false;
}

std::vector<std::string> post_dialect_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(std::string(data_dir()) + "/dialects", ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

// A problem of `post` as a reader dialect: names the file, or the dialect when made in code.
Diagnostic reader_error(const PostDialect& post, const std::string& message) {
  return make_error(post.file.empty() ? "dialect '" + post.name + "': " + message : message, post.file);
}

// The M codes written by the lines of one dialect field, in order, with the writer's
// placeholders standing for a number.
Result<std::vector<int>> m_codes(const PostDialect& post, const char* field,
                                 const std::vector<std::string>& lines) {
  std::vector<int> codes;
  for (const std::string& written : lines) {
    const std::string line = fill_placeholders(written, "1", "1");
    std::string bad;
    const auto scan = detail::scan_block(line, [&](const detail::Word& w) {
      if (w.letter != 'M' || !bad.empty()) return;
      const double r = std::round(w.value);
      if (r != w.value || r < 0 || r > 99999)
        bad = "an M code is a whole number 0..99999";
      else
        codes.push_back(static_cast<int>(r));
    });
    if (scan.error != detail::ScanError::none) bad = detail::scan_message(scan);
    if (!bad.empty())
      return reader_error(post, "dialect field '" + std::string(field) + "': line '" + written +
                                    "' cannot be read back: " + bad);
  }
  return codes;
}

}  // namespace

bool beam_switches_under_compensation(const PostDialect& post) {
  if (!post.thc_on.empty() || !post.thc_off.empty()) return false;
  for (const auto& [field, lines] : {std::pair{"beam_on", &post.beam_on}, std::pair{"beam_off", &post.beam_off},
                                     std::pair{"pierce", &post.pierce}}) {
    const auto codes = m_codes(post, field, *lines);
    if (!codes) return false;
    for (int m : *codes)
      if (m >= 62 && m <= 68) return false;  // digital / analog outputs
  }
  return true;
}

Result<Dialect> reader_dialect(const PostDialect& post) {
  auto on = m_codes(post, "beam_on", post.beam_on);
  if (!on) return on.error();
  auto off = m_codes(post, "beam_off", post.beam_off);
  if (!off) return off.error();
  Dialect d;
  d.name = post.name;
  d.beam_on = std::move(*on);
  d.beam_off = std::move(*off);
  d.dwell_p_unit = fanuc_dwell(post) ? DwellUnit::milliseconds : DwellUnit::seconds;
  if (d.beam_on.empty())
    return reader_error(
        post, "dialect field 'beam_on' writes no M code: a reader cannot tell where cutting starts");
  for (const auto& [field, codes] : {std::pair{"beam_on", &d.beam_on}, std::pair{"beam_off", &d.beam_off}}) {
    for (int m : *codes)
      if (fixed_meaning_m(m))
        return reader_error(post, "dialect field '" + std::string(field) + "' writes M" + std::to_string(m) +
                                      ", which has a fixed meaning and cannot switch the beam");
  }
  for (int m : d.beam_on)
    if (d.switches_off(m))
      return reader_error(post, "dialect fields 'beam_on' and 'beam_off' both write M" + std::to_string(m));

  const std::pair<const char*, std::vector<std::string>> others[] = {
      {"header", post.header},           {"footer", post.footer},       {"pierce", post.pierce},
      {"thc_on", post.thc_on},           {"thc_off", post.thc_off},     {"kerf_left", {post.kerf_left}},
      {"kerf_right", {post.kerf_right}}, {"kerf_off", {post.kerf_off}}, {"program_end", {post.program_end}}};
  for (const auto& [field, lines] : others) {
    auto codes = m_codes(post, field, lines);
    if (!codes) return codes.error();
    for (int m : *codes)
      if (!fixed_meaning_m(m) && !d.switches_on(m) && !d.switches_off(m)) d.inert.push_back(m);
  }
  for (auto* codes : {&d.beam_on, &d.beam_off, &d.inert}) {
    std::sort(codes->begin(), codes->end());
    codes->erase(std::unique(codes->begin(), codes->end()), codes->end());
  }
  return d;
}

}  // namespace cutroute::nc
