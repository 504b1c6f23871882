#include "io/dxf_scan.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/text.hpp>
#include <cutroute/core/units.hpp>

namespace cutroute::io::detail {

namespace {

// dxflib reads lines into a 1024-byte buffer; longer values of forwarded entities are cut
// (they can only be names, and we take names from the scan, not from dxflib).
constexpr std::size_t kMaxForwardedValue = 1000;

enum class Kind { text, real, integer };

Kind kind_of(int code) {
  if ((code >= 10 && code <= 59) || (code >= 110 && code <= 149) || (code >= 210 && code <= 239) ||
      (code >= 460 && code <= 469) || (code >= 1010 && code <= 1059))
    return Kind::real;
  if ((code >= 60 && code <= 99) || (code >= 160 && code <= 179) || (code >= 270 && code <= 299) ||
      (code >= 370 && code <= 389) || (code >= 400 && code <= 409) || (code >= 420 && code <= 429) ||
      (code >= 440 && code <= 459) || (code >= 1060 && code <= 1071))
    return Kind::integer;
  return Kind::text;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The iconv charset of a $DWGCODEPAGE value: "ANSI_1252" -> "CP1252" (likewise 874, 932, 936,
// 949, 950, 1250-1258), "DOS850" -> "IBM850"; anything else -> "CP1252", AutoCAD's default.
std::string iconv_charset(std::string_view page) {
  std::string up;
  for (const char c : page) up += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const auto digits = [](std::string_view d) {
    return !d.empty() && d.size() <= 5 && std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const std::string_view u(up);
  if (u.starts_with("ANSI_") && digits(u.substr(5))) return "CP" + std::string(u.substr(5));
  if (u.starts_with("DOS") && digits(u.substr(3))) return "IBM" + std::string(u.substr(3));
  return "CP1252";
}

// A name as the drawing wrote it, in UTF-8: bytes in the drawing's code page converted (files
// before AutoCAD 2007 are in one; later ones in UTF-8, kept), and the "\U+XXXX" escapes AutoCAD
// 2000-2004 write for characters outside their code page decoded.
std::string drawing_text(std::string_view v, const char* charset) {
  std::string s = to_utf8(v, charset);
  const auto hex = [](char c) {
    return c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
  };
  for (std::size_t at = s.find("\\U+"); at != std::string::npos; at = s.find("\\U+", at + 1)) {
    if (at + 7 > s.size()) break;
    unsigned cp = 0;
    bool ok = true;
    for (std::size_t k = at + 3; k < at + 7; ++k) {
      const int h = hex(s[k]);
      ok = ok && h >= 0;
      cp = cp * 16 + static_cast<unsigned>(std::max(h, 0));
    }
    if (!ok || cp == 0 || (cp >= 0xD800 && cp <= 0xDFFF)) continue;
    std::string u;
    if (cp < 0x80) {
      u += static_cast<char>(cp);
    } else if (cp < 0x800) {
      u += static_cast<char>(0xC0 | (cp >> 6));
      u += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      u += static_cast<char>(0xE0 | (cp >> 12));
      u += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      u += static_cast<char>(0x80 | (cp & 0x3F));
    }
    s.replace(at, 7, u);
  }
  return s;
}

// Parses a real the way DXF writers write them ("1.5", "-2", "1e-3", "+4", "1,5" from
// decimal-comma locales, which dxflib also accepts). Returns false for anything else.
bool parse_real(std::string_view s, double& v) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  std::string tmp;
  if (s.find(',') != std::string_view::npos && s.find('.') == std::string_view::npos) {
    tmp.assign(s);
    std::replace(tmp.begin(), tmp.end(), ',', '.');
    s = tmp;
  }
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc{} && r.ptr == s.data() + s.size();
}

bool parse_int(std::string_view s, long& v) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec == std::errc{} && r.ptr == s.data() + s.size()) return true;
  // Some writers put integers as reals ("1.0"): accept when integral.
  double d = 0;
  if (parse_real(s, d) && std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9e15) {
    v = static_cast<long>(d);
    return true;
  }
  return false;
}

bool known_section(std::string_view name) {
  static constexpr std::string_view kKnown[] = {"HEADER", "CLASSES", "TABLES", "BLOCKS", "ENTITIES",
                                                "OBJECTS", "THUMBNAILIMAGE", "ACDSDATA"};
  return std::find(std::begin(kKnown), std::end(kKnown), name) != std::end(kKnown);
}

bool is_forwarded_type(std::string_view t) {
  return t == "LINE" || t == "ARC" || t == "CIRCLE" || t == "ELLIPSE" || t == "LWPOLYLINE" || t == "POLYLINE" ||
         t == "SPLINE" || t == "INSERT";
}

bool forwarded_code(int code) {
  switch (code) {
    case 2: case 10: case 20: case 11: case 21: case 12: case 22: case 13: case 23:
    case 40: case 41: case 42: case 44: case 45: case 50: case 51:
    case 70: case 71: case 72: case 73: case 74: case 90:
    case 210: case 220: case 230:
      return true;
    default:
      return false;
  }
}

struct Pair {
  int code;
  std::string_view value;  // untrimmed
};

// Per-entity counters for the checks dxflib does not do.
struct Counts {
  long n10 = 0, n11 = 0, n40 = 0, n41 = 0;
  std::optional<long> c90, c72, c73, c74;
  bool bulge_before_vertex = false;
};

class Scanner {
 public:
  Scanner(std::string_view content, const std::string& file, UnitsRule rule, const void* ctx)
      : s_(content), file_(file), rule_(rule), ctx_(ctx) {}

  Result<ScanResult> run();

 private:
  bool next_line(std::string_view& line);
  // Messages quote values from the file, which may be in the drawing's code page.
  Diagnostic error(std::string msg, std::optional<long> line) const {
    return make_error(to_utf8(msg, charset_.c_str()), file_, line);
  }
  // A name from the drawing (layer, block) in UTF-8: see drawing_text().
  std::string text(std::string_view v) const { return drawing_text(v, charset_.c_str()); }
  std::optional<Diagnostic> check_value(int code, std::string_view value, long line);
  std::optional<Diagnostic> finish_entity();
  void start_entity(std::string_view type, long line);
  std::optional<Diagnostic> entity_pair(int code, std::string_view value, long line);
  double coordinate_limit();

  std::string_view s_;
  std::size_t pos_ = 0;
  long line_no_ = 0;
  const std::string& file_;
  UnitsRule rule_;
  const void* ctx_;
  std::optional<double> limit_units_;
  double last_real_ = 0;  // value of the last real group checked

  ScanResult r_;
  std::string section_;
  bool entities_seen_ = false;
  bool entities_closed_ = false;
  // Current entity
  int cur_ = -1;
  std::vector<Pair> cur_pairs_;
  Counts counts_;
  int owner_ = -1;        // last POLYLINE/INSERT of the current container
  int block_ = -1;        // current block index while inside BLOCK ... ENDBLK
  bool in_block_header_ = false;
  bool in_endblk_ = false;
  std::size_t paperspace_skipped_ = 0;
  // The LAYER table entry being read (TABLES section): its name, flags and colour.
  struct LayerEntry {
    bool open = false;
    std::string name;
    long flags = 0, colour = 0;
  } layer_entry_;
  void finish_layer_entry() {
    if (!layer_entry_.open) return;
    const bool frozen = (layer_entry_.flags & 1) != 0, off = layer_entry_.colour < 0;
    if (frozen || off)
      r_.hidden_layers.emplace_back(layer_entry_.name, off && frozen ? "off and frozen" : off ? "off" : "frozen");
    layer_entry_ = LayerEntry{};
  }
  std::string charset_ = "CP1252";  // iconv name of $DWGCODEPAGE (AutoCAD's default when absent)
};

bool Scanner::next_line(std::string_view& line) {
  if (pos_ >= s_.size()) return false;
  const std::size_t start = pos_;
  std::size_t i = start;
  while (i < s_.size() && s_[i] != '\n' && s_[i] != '\r') ++i;
  line = s_.substr(start, i - start);
  if (i < s_.size()) {
    if (s_[i] == '\r' && i + 1 < s_.size() && s_[i + 1] == '\n') i += 2;
    else ++i;
  }
  pos_ = i;
  ++line_no_;
  return true;
}

double Scanner::coordinate_limit() {
  if (!limit_units_) {
    const double mm_per_unit = rule_(r_.insunits, r_.measurement, ctx_);
    limit_units_ = units::kMaxCoordinateMm / mm_per_unit;
  }
  return *limit_units_;
}

std::optional<Diagnostic> Scanner::check_value(int code, std::string_view value, long line) {
  const Kind k = kind_of(code);
  auto fail = [&](const char* what) {
    return error("group code " + std::to_string(code) + ": '" + std::string(trim(value)) + "' " + what, line);
  };
  if (k != Kind::text && trim(value).size() > kMaxForwardedValue) {
    return error("group code " + std::to_string(code) + ": number of more than 1000 characters", line);
  }
  if (k == Kind::real) {
    double v = 0;
    if (!parse_real(value, v)) return fail("is not a number");
    if (!std::isfinite(v)) return fail("is not a finite number");
    last_real_ = v;
    const bool geometry_section = section_ == "ENTITIES" || section_ == "BLOCKS";
    if (geometry_section && code >= 10 && code <= 39 && std::abs(v) > coordinate_limit()) {
      // In drawing units that are not mm, the value in mm too: it is what the limit is about.
      const double mm = v * units::kMaxCoordinateMm / coordinate_limit();
      const std::string in_mm = std::abs(mm - v) > 1e-9 * std::abs(v) ? " (" + format_fixed(mm, 0) + " mm)" : "";
      return error("group code " + std::to_string(code) + ": coordinate " + std::string(trim(value)) + in_mm +
                       " is out of range (more than 1e6 mm from the origin)",
                   line);
    }
  } else if (k == Kind::integer) {
    long v = 0;
    if (!parse_int(value, v)) return fail("is not an integer");
  }
  return std::nullopt;
}

void Scanner::start_entity(std::string_view type, long line) {
  ScanEntity e;
  e.type.assign(type);
  e.line = line;
  e.block = block_;
  const int idx = static_cast<int>(r_.entities.size());
  if (e.type == "VERTEX" || e.type == "SEQEND" || e.type == "ATTRIB") {
    e.owner = owner_;
    if (e.type == "SEQEND") owner_ = -1;
  } else {
    owner_ = (e.type == "POLYLINE" || e.type == "INSERT") ? idx : -1;
  }
  if (e.type == "SPLINE") {
    e.spline = static_cast<int>(r_.splines.size());
    r_.splines.emplace_back();
  }
  r_.entities.push_back(std::move(e));
  cur_ = idx;
  cur_pairs_.clear();
  counts_ = Counts{};
}

std::optional<Diagnostic> Scanner::entity_pair(int code, std::string_view value, long line) {
  ScanEntity& e = r_.entities[static_cast<std::size_t>(cur_)];
  const std::string_view v = trim(value);
  long iv = 0;
  switch (code) {
    case 5: if (e.handle.empty()) e.handle.assign(v); break;
    case 8: e.layer = text(v); break;
    case 2: if (e.type == "INSERT") e.block_name = text(v); break;
    case 67: if (parse_int(v, iv)) e.paperspace = iv == 1; break;
    case 60: if (parse_int(v, iv)) e.invisible = iv == 1; break;
    case 30:
      // In an entity's own coordinate system the first z is its plane's height, which moves it
      // sideways when the plane is tilted (LINE, ELLIPSE, SPLINE and VERTEX z are not).
      if (!e.has_elevation && (e.type == "ARC" || e.type == "CIRCLE" || e.type == "INSERT" || e.type == "POLYLINE"))
        e.elevation = last_real_, e.has_elevation = true;
      break;
    case 38:
      if (e.type == "LWPOLYLINE") e.elevation = last_real_, e.has_elevation = true;
      break;
    case 70:
      if (parse_int(v, iv)) {
        e.flags = static_cast<int>(std::clamp(iv, -1000000L, 1000000L));
      }
      break;
    case 10: ++counts_.n10; break;
    case 11: ++counts_.n11; break;
    case 40: ++counts_.n40; break;
    case 41: ++counts_.n41; break;
    default: break;
  }
  if (e.spline >= 0) {
    ScanSpline& sp = r_.splines[static_cast<std::size_t>(e.spline)];
    switch (code) {
      case 40: sp.knots.push_back(last_real_); break;
      case 41: sp.weights.push_back(last_real_); break;
      case 10: sp.control.push_back({last_real_, 0.0}); break;
      case 20: if (!sp.control.empty()) sp.control.back().y = last_real_; break;
      case 11: sp.fit.push_back({last_real_, 0.0}); break;
      case 21: if (!sp.fit.empty()) sp.fit.back().y = last_real_; break;
      default: break;
    }
  }
  switch (code) {
    case 42: if (counts_.n10 == 0) counts_.bulge_before_vertex = true; break;
    case 90: if (parse_int(v, iv)) counts_.c90 = iv; break;
    case 72: if (parse_int(v, iv)) counts_.c72 = iv; break;
    case 73: if (parse_int(v, iv)) counts_.c73 = iv; break;
    case 74: if (parse_int(v, iv)) counts_.c74 = iv; break;
    default: break;
  }
  (void)line;
  cur_pairs_.push_back({code, value});
  return std::nullopt;
}

std::optional<Diagnostic> Scanner::finish_entity() {
  if (cur_ < 0) return std::nullopt;
  ScanEntity& e = r_.entities[static_cast<std::size_t>(cur_)];
  const int idx = cur_;
  cur_ = -1;
  const long line = e.line;
  auto count_error = [&](const char* what, long declared, long actual, int code) {
    return error(e.type + " declares " + std::to_string(declared) + " " + what + " (group " + std::to_string(code) +
                     ") but has " + std::to_string(actual),
                 line);
  };
  if (e.type == "LWPOLYLINE") {
    if (counts_.bulge_before_vertex) return error("LWPOLYLINE has a bulge (group 42) before its first vertex", line);
    if (counts_.c90.value_or(0) != counts_.n10) return count_error("vertices", counts_.c90.value_or(0), counts_.n10, 90);
  } else if (e.type == "SPLINE") {
    if (counts_.c72.value_or(0) != counts_.n40) return count_error("knots", counts_.c72.value_or(0), counts_.n40, 72);
    if (counts_.c73.value_or(0) != counts_.n10) return count_error("control points", counts_.c73.value_or(0), counts_.n10, 73);
    if (counts_.c74.value_or(0) != counts_.n11) return count_error("fit points", counts_.c74.value_or(0), counts_.n11, 74);
    if (counts_.n41 > counts_.n10) return count_error("control points", counts_.n10, counts_.n41, 41);
  }
  // Top-level bookkeeping.
  const bool sub = e.owner >= 0 || e.type == "VERTEX" || e.type == "SEQEND" || e.type == "ATTRIB";
  if (!sub) {
    if (e.block >= 0) {
      r_.blocks[static_cast<std::size_t>(e.block)].entities.push_back(idx);
    } else if (e.paperspace) {
      ++paperspace_skipped_;
    } else {
      r_.modelspace.push_back(idx);
    }
  }
  // Forwarding decision.
  bool fwd = false;
  if (e.owner >= 0) {
    const ScanEntity& o = r_.entities[static_cast<std::size_t>(e.owner)];
    fwd = o.forwarded && o.type == "POLYLINE" && (e.type == "VERTEX" || e.type == "SEQEND");
  } else if (!sub) {
    fwd = is_forwarded_type(e.type) && !(e.block < 0 && e.paperspace);
    // Polyface and polygon meshes are 3D surfaces, not curves.
    if (e.type == "POLYLINE" && (e.flags & (16 | 64)) != 0) fwd = false;
  }
  e.forwarded = fwd;
  if (fwd) {
    std::string& t = r_.dxflib_text;
    t += "0\n";
    t += e.type;
    t += '\n';
    r_.zero_offsets.push_back(t.size());
    r_.zero_entities.push_back(idx);
    // dxflib keeps vertex/knot/control/fit counts from the previous entity when a count group
    // is absent; an explicit 0 (the scan checked that there is no data) resets them.
    if (e.type == "LWPOLYLINE" && !counts_.c90) t += "90\n0\n";
    const bool spline = e.type == "SPLINE";
    if (spline) t += "72\n0\n73\n0\n74\n0\n";  // arrays come from the scan (ScanSpline)
    for (const Pair& p : cur_pairs_) {
      if (spline && (p.code == 10 || p.code == 20 || p.code == 11 || p.code == 21 || p.code == 40 || p.code == 41 ||
                     p.code == 72 || p.code == 73 || p.code == 74)) {
        continue;
      }
      // Only the groups the reader takes from dxflib: less to parse (dxflib converts every
      // number through a string stream), and nothing that can confuse its state machine
      // (group 9 starts a header variable there, 1000+ are extended data). Z coordinates are
      // dropped: the reader projects onto the XY plane.
      if (!forwarded_code(p.code)) continue;
      std::string_view v = trim(p.value);
      if (v.size() > kMaxForwardedValue) v = v.substr(0, kMaxForwardedValue);
      char buf[8];
      const auto r = std::to_chars(buf, buf + sizeof buf, p.code);
      t.append(buf, r.ptr);
      t += '\n';
      t += v;
      t += '\n';
    }
  }
  return std::nullopt;
}

Result<ScanResult> Scanner::run() {
  if (s_.size() >= 3 && static_cast<unsigned char>(s_[0]) == 0xEF && static_cast<unsigned char>(s_[1]) == 0xBB &&
      static_cast<unsigned char>(s_[2]) == 0xBF) {
    pos_ = 3;  // UTF-8 byte order mark
  }
  if (s_.substr(0, 18) == "AutoCAD Binary DXF") return error("binary DXF files are not supported (save as ASCII DXF)", 1);
  if (trim(s_).find_first_not_of("\r\n") == std::string_view::npos) return error("file is empty", 1);

  r_.dxflib_text.reserve(s_.size() / 2 + 64);
  r_.dxflib_text = "0\nSECTION\n2\nENTITIES\n";

  enum class State { top, section_name, section };
  State state = State::top;
  long section_line = 0;
  bool eof_seen = false;
  std::string var;  // current header variable
  std::string_view code_line, value_line;
  while (next_line(code_line)) {
    const long code_no = line_no_;
    for (unsigned char ch : code_line) {
      if (ch < 0x20 && ch != '\t') {
        char buf[8];
        std::snprintf(buf, sizeof buf, "0x%02X", ch);
        return error(std::string("binary data (byte ") + buf + ") in a text DXF file", code_no);
      }
    }
    const std::string_view code_text = trim(code_line);
    long code_l = 0;
    {
      const auto r = std::from_chars(code_text.data(), code_text.data() + code_text.size(), code_l);
      if (code_text.empty() || r.ec != std::errc{} || r.ptr != code_text.data() + code_text.size()) {
        std::string shown(code_text.substr(0, 40));
        // On the first pair the file is no DXF at all (a G-code program, an SVG, a DWG export
        // name mix-up): say so rather than blame one group code.
        if (code_no == 1)
          return error("not a DXF drawing: a text DXF starts with a group code (0) and SECTION, this file with '" + shown + "'", code_no);
        return error("group code '" + shown + "' is not an integer", code_no);
      }
    }
    if (code_l < 0 || code_l > 1071) return error("group code " + std::to_string(code_l) + " is out of range", code_no);
    const int code = static_cast<int>(code_l);
    if (!next_line(value_line)) {
      return error("group code " + std::to_string(code) + " has no value: the file is truncated", code_no);
    }
    const long value_no = line_no_;
    for (unsigned char ch : value_line) {
      if (ch < 0x20 && ch != '\t') {
        char buf[8];
        std::snprintf(buf, sizeof buf, "0x%02X", ch);
        return error(std::string("binary data (byte ") + buf + ") in a text DXF file", value_no);
      }
    }
    if (code == 999) continue;  // comment
    if (auto d = check_value(code, value_line, value_no)) return *d;
    const std::string_view value = trim(value_line);

    switch (state) {
      case State::top:
        if (code != 0) return error("group code " + std::to_string(code) + " outside a section (expected 0/SECTION)", code_no);
        if (value == "SECTION") {
          state = State::section_name;
          section_line = code_no;
        } else if (value == "EOF") {
          eof_seen = true;
        } else {
          return error("expected SECTION or EOF, found '" + std::string(value.substr(0, 40)) + "'", value_no);
        }
        break;
      case State::section_name:
        if (code != 2) return error("SECTION has no name (group 2)", code_no);
        if (!known_section(value)) return error("unknown section '" + std::string(value.substr(0, 40)) + "'", value_no);
        section_.assign(value);
        if (section_ == "ENTITIES") {
          if (entities_seen_) return error("second ENTITIES section", value_no);
          entities_seen_ = true;
        }
        state = State::section;
        break;
      case State::section: {
        const bool geometry = section_ == "ENTITIES" || section_ == "BLOCKS";
        if (code == 0 && (value == "ENDSEC" || value == "SECTION" || value == "EOF")) {
          if (auto d = finish_entity()) return *d;
          if (value != "ENDSEC") {
            return error("section " + section_ + " (line " + std::to_string(section_line) + ") has no ENDSEC before " +
                             std::string(value),
                         code_no);
          }
          if (section_ == "BLOCKS" && block_ >= 0 && !in_endblk_) {
            return error("BLOCK '" + r_.blocks[static_cast<std::size_t>(block_)].name + "' has no ENDBLK", code_no);
          }
          if (section_ == "ENTITIES") entities_closed_ = true;
          finish_layer_entry();
          block_ = -1;
          in_endblk_ = false;
          in_block_header_ = false;
          owner_ = -1;
          state = State::top;
          section_.clear();
          break;
        }
        if (section_ == "TABLES") {
          if (code == 0) {
            finish_layer_entry();
            layer_entry_.open = value == "LAYER";
          } else if (layer_entry_.open) {
            long iv = 0;
            if (code == 2) layer_entry_.name = text(value);
            else if (code == 70 && parse_int(value, iv)) layer_entry_.flags = iv;
            else if (code == 62 && parse_int(value, iv)) layer_entry_.colour = iv;
          }
          break;
        }
        if (section_ == "HEADER") {
          if (code == 9) {
            var.assign(value);
          } else if (code == 3 && var == "$DWGCODEPAGE") {
            charset_ = iconv_charset(trim(value));
          } else if (code == 70 && (var == "$INSUNITS" || var == "$MEASUREMENT")) {
            long v = 0;
            parse_int(value, v);
            (var == "$INSUNITS" ? r_.insunits : r_.measurement) = static_cast<int>(std::clamp(v, -1000L, 1000L));
          }
          break;
        }
        if (!geometry) break;
        if (code == 0) {
          if (auto d = finish_entity()) return *d;
          if (section_ == "BLOCKS") {
            if (value == "BLOCK") {
              if (block_ >= 0 && !in_endblk_) {
                return error("BLOCK '" + r_.blocks[static_cast<std::size_t>(block_)].name + "' has no ENDBLK", code_no);
              }
              ScanBlock b;
              b.line = code_no;
              r_.blocks.push_back(std::move(b));
              block_ = static_cast<int>(r_.blocks.size()) - 1;
              in_block_header_ = true;
              in_endblk_ = false;
              owner_ = -1;
              break;
            }
            if (value == "ENDBLK") {
              if (block_ < 0 || in_endblk_) return error("ENDBLK without BLOCK", code_no);
              in_block_header_ = false;
              in_endblk_ = true;
              break;
            }
            if (block_ < 0 || in_endblk_) {
              return error("entity " + std::string(value.substr(0, 40)) + " outside a BLOCK in the BLOCKS section", code_no);
            }
            in_block_header_ = false;
          }
          start_entity(value, code_no);
          break;
        }
        if (section_ == "BLOCKS" && (in_block_header_ || in_endblk_)) {
          if (in_block_header_) {
            ScanBlock& b = r_.blocks[static_cast<std::size_t>(block_)];
            double d = 0;
            long iv = 0;
            if (code == 2) b.name = text(value);
            else if (code == 10 && parse_real(value, d)) b.base.x = d;
            else if (code == 20 && parse_real(value, d)) b.base.y = d;
            else if (code == 70 && parse_int(value, iv)) b.flags = static_cast<int>(std::clamp(iv, -100000L, 100000L));
          }
          break;
        }
        if (cur_ < 0) return error("group code " + std::to_string(code) + " before the first entity", code_no);
        if (auto d = entity_pair(code, value_line, value_no)) return *d;
        break;
      }
    }
    if (eof_seen) break;
  }
  if (!eof_seen) {
    // A file cut off after its ENTITIES section (in OBJECTS, say) still has all its geometry.
    const bool after_entities = entities_closed_ && section_ != "BLOCKS";
    if (state != State::top && after_entities) {
      r_.warnings.push_back(make_warning("file is truncated after the ENTITIES section (in section " +
                                             (section_.empty() ? std::string("?") : section_) + ")",
                                         file_, line_no_));
      r_.warnings.back().code = "dxf.truncated";
    } else if (state == State::section_name) {
      return error("file is truncated after SECTION", section_line);
    } else if (state == State::section) {
      if ((section_ == "ENTITIES" || section_ == "BLOCKS") && cur_ >= 0) {
        const ScanEntity& e = r_.entities[static_cast<std::size_t>(cur_)];
        return error("file is truncated inside the " + e.type + " entity starting at this line (no ENDSEC/EOF)", e.line);
      }
      return error("file is truncated in section " + section_ + " (no ENDSEC/EOF)", line_no_);
    } else {
      r_.warnings.push_back(make_warning("file has no EOF marker", file_, line_no_));
    }
  }
  if (!entities_seen_) return error("no ENTITIES section", std::nullopt);
  if (paperspace_skipped_ > 0) {
    Diagnostic w = make_warning(std::to_string(paperspace_skipped_) + " paper-space entities ignored", file_);
    w.code = "dxf.paper_space";
    r_.warnings.push_back(std::move(w));
  }
  r_.dxflib_text += "0\nENDSEC\n";
  r_.zero_offsets.push_back(r_.dxflib_text.size());
  r_.zero_entities.push_back(-1);
  r_.dxflib_text += "0\nEOF\n";
  return std::move(r_);
}

}  // namespace

std::optional<double> insunits_mm(int code) {
  switch (code) {
    case 1: return units::kMmPerInch;
    case 2: return units::kMmPerFoot;
    case 4: return 1.0;
    case 5: return units::kMmPerCm;
    case 6: return units::kMmPerM;
    case 8: return units::kMmPerInch * 1e-6;  // microinch
    case 9: return units::kMmPerInch * 1e-3;  // mil
    case 10: return 3 * units::kMmPerFoot;    // yard
    case 13: return 1e-3;                     // micron
    case 14: return 100.0;                    // decimetre
    default: return std::nullopt;
  }
}

const char* insunits_name(int code) {
  switch (code) {
    case 0: return "unitless";
    case 1: return "in";
    case 2: return "ft";
    case 3: return "mi";
    case 4: return "mm";
    case 5: return "cm";
    case 6: return "m";
    case 7: return "km";
    case 8: return "uin";
    case 9: return "mil";
    case 10: return "yd";
    case 13: return "um";
    case 14: return "dm";
    default: return "unknown";
  }
}

Result<ScanResult> scan_dxf(std::string_view content, const std::string& file, UnitsRule mm_per_unit,
                            const void* units_ctx) {
  Scanner s(content, file, mm_per_unit, units_ctx);
  return s.run();
}

}  // namespace cutroute::io::detail
