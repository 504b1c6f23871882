#include <cutroute/io/instance.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <cutroute/core/file.hpp>

#include "instance_distance.hpp"

namespace cutroute::io {

const char* to_string(InstanceFormat f) {
  switch (f) {
    case InstanceFormat::gtsp: return "gtsp";
    case InstanceFormat::sop: return "sop";
    case InstanceFormat::pcglns: return "pcglns";
  }
  return "?";
}

namespace {

using solve::ClusterId;
using solve::Cost;
using solve::NodeId;

// Above this many nodes coordinates are kept and distances computed on demand (a full matrix of
// 3000 nodes is 72 MB; 100C10k.0 has 10 000 nodes).
constexpr int kMaxMatrixNodes = 3000;
// Largest DIMENSION / GTSP_SETS accepted, so a typo cannot make us allocate terabytes.
constexpr long kMaxDimension = 1'000'000;
// Largest |coordinate|: every TSPLIB distance between such points stays below solve::kMaxCost (2^40),
// and a huge value cannot overflow the conversion to an integer cost.
constexpr double kMaxCoordinate = 1.0e11;

// A line is kept as its text and split into words only where it is read: a table of every word
// (16 bytes each, twice that while the vector grew) took twice the memory of the matrix it held,
// 262 MB for a 4 000-node FULL_MATRIX.
struct Line {
  long number = 0;
  std::string_view text;
};

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  long number = 0;
  std::size_t i = 0;
  while (i <= text.size()) {
    std::size_t j = i;
    while (j < text.size() && text[j] != '\n' && text[j] != '\r') ++j;
    lines.push_back({++number, text.substr(i, j - i)});
    if (j >= text.size()) break;
    // CRLF counts as one line break, a lone CR or LF as one.
    i = (text[j] == '\r' && j + 1 < text.size() && text[j + 1] == '\n') ? j + 2 : j + 1;
  }
  return lines;
}

bool space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// The next word of `text` at or after offset `at` (empty at the end); `at` moves past it.
std::string_view next_word(std::string_view text, std::size_t& at) {
  while (at < text.size() && space(text[at])) ++at;
  const std::size_t b = at;
  while (at < text.size() && !space(text[at])) ++at;
  return text.substr(b, at - b);
}

std::vector<std::string_view> words(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t at = 0;
  for (auto w = next_word(text, at); !w.empty(); w = next_word(text, at)) out.push_back(w);
  return out;
}

std::size_t count_words(std::string_view text) {
  std::size_t k = 0, at = 0;
  while (!next_word(text, at).empty()) ++k;
  return k;
}

std::string_view first_word(const Line& l) {
  std::size_t at = 0;
  return next_word(l.text, at);
}

bool is_keyword_line(const Line& l) {
  const auto w = first_word(l);
  return !w.empty() && std::isalpha(static_cast<unsigned char>(w[0]));
}

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

class Parser {
 public:
  Parser(std::string_view text, std::string file, std::optional<InstanceFormat> format)
      : lines_(split_lines(text)), file_(std::move(file)), format_(format) {}

  Result<Instance> run();

 private:
  Diagnostic error(long line, const std::string& msg) const { return make_error(msg, file_, line); }
  long line_no() const { return li_ < lines_.size() ? lines_[li_].number : (lines_.empty() ? 1 : lines_.back().number); }

  // Next number of the current section (numbers may wrap across lines); an error at a keyword or EOF.
  std::optional<Diagnostic> next_integer(long long& out, const char* what);
  std::optional<Diagnostic> next_real(double& out, const char* what);
  std::optional<std::string_view> next_token();

  std::optional<Diagnostic> parse_header_line(const Line& l);
  std::optional<Diagnostic> need_dimension(long line, const char* section);
  std::optional<Diagnostic> parse_coords();
  std::optional<Diagnostic> parse_weights();
  std::optional<Diagnostic> parse_sets();
  std::optional<Diagnostic> parse_ordering();
  std::optional<Diagnostic> parse_start_group();
  void skip_section();
  Result<Instance> finish();

  std::vector<Line> lines_;
  std::string file_;
  std::optional<InstanceFormat> format_;
  std::size_t li_ = 0, ci_ = 0;  // cursor: line, character offset in it

  std::string name_, type_, weight_type_, weight_format_;
  long type_line_ = 0, weight_type_line_ = 0;
  long n_ = -1, m_ = -1;
  std::vector<detail::Coord> coords_;
  std::vector<Cost> matrix_;
  std::vector<std::vector<NodeId>> sets_;
  std::vector<std::pair<ClusterId, ClusterId>> order_;
  std::vector<long> order_lines_;
  // Checked here rather than left to ProblemBuilder::build(), whose messages know neither lines
  // nor the file's 1-based ids.
  long sets_line_ = 0;           // GTSP_SET_SECTION
  struct MinusOne {
    std::size_t i, j;
    long line;
  };
  std::vector<MinusOne> minus_ones_;  // -1 weights: forbidden arcs, in SOP precedences
  Cost max_weight_ = 0;
  long max_weight_line_ = 0;
  std::optional<Diagnostic> check_orders(const std::vector<std::pair<ClusterId, ClusterId>>& pairs, const std::vector<long>& lines,
                                         const char* what) const;
  long start_group_ = 1;
  long start_group_line_ = 0;
  bool have_coords_ = false, have_weights_ = false, have_sets_ = false;
};

std::optional<std::string_view> Parser::next_token() {
  while (li_ < lines_.size()) {
    const Line& l = lines_[li_];
    if (ci_ == 0 && is_keyword_line(l)) return std::nullopt;
    if (const auto w = next_word(l.text, ci_); !w.empty()) return w;
    ++li_;
    ci_ = 0;
  }
  return std::nullopt;
}

std::optional<Diagnostic> Parser::next_integer(long long& out, const char* what) {
  const auto tok = next_token();
  if (!tok) return error(line_no(), std::string("section ended early: expected ") + what);
  const auto* b = tok->data();
  const auto* e = b + tok->size();
  const auto r = std::from_chars(b, e, out);
  if (r.ec == std::errc() && r.ptr == e) return std::nullopt;
  // Explicit weights written as "12.0": accept integral reals.
  double d = 0;
  const auto rd = std::from_chars(b, e, d);
  if (rd.ec == std::errc() && rd.ptr == e && d == std::floor(d) && std::fabs(d) < 9.0e15) {
    out = static_cast<long long>(d);
    return std::nullopt;
  }
  return error(line_no(), std::string("expected an integer (") + what + "), got '" + std::string(*tok) + "'");
}

std::optional<Diagnostic> Parser::next_real(double& out, const char* what) {
  const auto tok = next_token();
  if (!tok) return error(line_no(), std::string("section ended early: expected ") + what);
  const auto* e = tok->data() + tok->size();
  const auto r = std::from_chars(tok->data(), e, out);
  if (r.ec != std::errc() || r.ptr != e || !std::isfinite(out))
    return error(line_no(), std::string("expected a number (") + what + "), got '" + std::string(*tok) + "'");
  return std::nullopt;
}

void Parser::skip_section() {
  while (li_ < lines_.size() && !is_keyword_line(lines_[li_])) ++li_;
  ci_ = 0;
}

std::optional<Diagnostic> Parser::need_dimension(long line, const char* section) {
  if (n_ < 0) return error(line, std::string("DIMENSION must be given before ") + section);
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_header_line(const Line& l) {
  // "KEY : VALUE", "KEY: VALUE", "KEY VALUE" (35ftv170 has "TYPE  AGTSP").
  std::string joined;
  for (const auto w : words(l.text)) {
    if (!joined.empty()) joined.push_back(' ');
    joined.append(w);
  }
  std::string key, value;
  const auto colon = joined.find(':');
  if (colon != std::string::npos) {
    key = trim(std::string_view(joined).substr(0, colon));
    value = trim(std::string_view(joined).substr(colon + 1));
  } else {
    const auto sp = joined.find(' ');
    key = joined.substr(0, sp);
    value = sp == std::string::npos ? "" : trim(std::string_view(joined).substr(sp + 1));
  }
  auto number = [&](long& out, const char* field) -> std::optional<Diagnostic> {
    // Sections already read were sized by the first value (a second one overran them).
    if (out >= 0) return error(l.number, std::string(field) + " given twice");
    long v = 0;
    const auto r = std::from_chars(value.data(), value.data() + value.size(), v);
    if (r.ec != std::errc() || r.ptr != value.data() + value.size() || v <= 0 || v > kMaxDimension)
      return error(l.number, std::string(field) + " must be a positive integer, got '" + value + "'");
    out = v;
    return std::nullopt;
  };
  if (key == "NAME") name_ = value;
  else if (key == "TYPE") type_ = value, type_line_ = l.number;
  else if (key == "DIMENSION") return number(n_, "DIMENSION");
  else if (key == "GTSP_SETS") return number(m_, "GTSP_SETS");
  else if (key == "EDGE_WEIGHT_TYPE") weight_type_ = value, weight_type_line_ = l.number;
  else if (key == "EDGE_WEIGHT_FORMAT" || key == "EDGE_WEIGHTS_FORMAT") weight_format_ = value;
  // COMMENT, NODE_COORD_TYPE, DISPLAY_DATA_TYPE, CAPACITY ...: not needed.
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_coords() {
  if (auto e = need_dimension(line_no(), "NODE_COORD_SECTION")) return e;
  coords_.assign(static_cast<std::size_t>(n_), {});
  std::vector<char> seen(static_cast<std::size_t>(n_), 0);
  for (long k = 0; k < n_; ++k) {
    long long id = 0;
    if (auto e = next_integer(id, "node id")) return e;
    if (id < 1 || id > n_) return error(line_no(), "node id " + std::to_string(id) + " outside 1.." + std::to_string(n_));
    if (seen[static_cast<std::size_t>(id - 1)]) return error(line_no(), "node " + std::to_string(id) + " given twice");
    seen[static_cast<std::size_t>(id - 1)] = 1;
    auto& c = coords_[static_cast<std::size_t>(id - 1)];
    if (auto e = next_real(c.x, "x coordinate")) return e;
    if (auto e = next_real(c.y, "y coordinate")) return e;
    if (std::fabs(c.x) > kMaxCoordinate || std::fabs(c.y) > kMaxCoordinate)
      return error(line_no(), "node " + std::to_string(id) + ": coordinate beyond +-1e11");
  }
  have_coords_ = true;
  skip_section();  // e.g. a third coordinate
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_weights() {
  const long at = line_no();
  if (auto e = need_dimension(at, "EDGE_WEIGHT_SECTION")) return e;
  if (n_ > kMaxMatrixNodes * 4L) return error(at, "explicit matrix of " + std::to_string(n_) + " nodes is too large");
  const auto n = static_cast<std::size_t>(n_);
  const bool sop = format_ == InstanceFormat::sop;
  if (sop) {
    // TSPLIB SOP repeats the dimension as the first number of the section.
    long long dim = 0;
    if (auto e = next_integer(dim, "dimension repeated at the start of EDGE_WEIGHT_SECTION")) return e;
    if (dim != n_) return error(line_no(), "EDGE_WEIGHT_SECTION starts with " + std::to_string(dim) + ", DIMENSION is " + std::to_string(n_));
  }
  std::string f = weight_format_.empty() ? "FULL_MATRIX" : weight_format_;
  // Column formats read the transposed triangle.
  if (f == "UPPER_COL") f = "LOWER_ROW";
  else if (f == "LOWER_COL") f = "UPPER_ROW";
  else if (f == "UPPER_DIAG_COL") f = "LOWER_DIAG_ROW";
  else if (f == "LOWER_DIAG_COL") f = "UPPER_DIAG_ROW";
  std::size_t need = 0;
  if (f == "FULL_MATRIX") need = n * n;
  else if (f == "UPPER_ROW" || f == "LOWER_ROW") need = n * (n - 1) / 2;
  else if (f == "UPPER_DIAG_ROW" || f == "LOWER_DIAG_ROW") need = n * (n + 1) / 2;
  else return error(at, "unsupported EDGE_WEIGHT_FORMAT '" + weight_format_ + "'");
  // The n x n matrix is allocated only once the section is seen to hold its numbers, so a short file
  // declaring a large DIMENSION cannot take gigabytes; extra numbers are an error too.
  std::size_t given = 0, end = li_;
  for (; end < lines_.size() && ((end == li_ && ci_ > 0) || !is_keyword_line(lines_[end])); ++end)
    given += count_words(lines_[end].text.substr(end == li_ ? ci_ : 0));
  if (given < need)
    return error(end < lines_.size() ? lines_[end].number : line_no(),
                 "section ended early: EDGE_WEIGHT_SECTION gives " + std::to_string(given) + " of the " + std::to_string(need) +
                     " weights " + f + " needs for DIMENSION " + std::to_string(n_));
  matrix_.assign(n * n, 0);
  auto read = [&](std::size_t i, std::size_t j, bool mirror) -> std::optional<Diagnostic> {
    long long v = 0;
    if (auto e = next_integer(v, "edge weight")) return e;
    if (v < 0) {
      if (v != -1 || !(sop || format_ == InstanceFormat::pcglns)) return error(line_no(), "negative edge weight " + std::to_string(v));
      v = solve::kForbiddenCost;
      if (i != j) {
        minus_ones_.push_back({i, j, line_no()});
        if (mirror) minus_ones_.push_back({j, i, line_no()});
      }
    } else if (v > solve::kMaxCost) {
      return error(line_no(), "edge weight " + std::to_string(v) + " exceeds 2^40");
    } else if (v > max_weight_ && i != j) {
      max_weight_ = v, max_weight_line_ = line_no();
    }
    matrix_[i * n + j] = v;
    if (mirror) matrix_[j * n + i] = v;
    return std::nullopt;
  };
  if (f == "FULL_MATRIX") {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        if (auto e = read(i, j, false)) return e;
  } else if (f == "UPPER_ROW" || f == "UPPER_DIAG_ROW") {
    const std::size_t d = f == "UPPER_ROW" ? 1 : 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + d; j < n; ++j)
        if (auto e = read(i, j, true)) return e;
  } else if (f == "LOWER_ROW" || f == "LOWER_DIAG_ROW") {
    const std::size_t d = f == "LOWER_ROW" ? 0 : 1;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i + d; ++j)
        if (auto e = read(i, j, true)) return e;
  }
  have_weights_ = true;
  if (given > need) {
    while (li_ < lines_.size() && count_words(lines_[li_].text.substr(ci_)) == 0) ++li_, ci_ = 0;
    return error(line_no(), "more edge weights than the format " + f + " holds for DIMENSION " + std::to_string(n_));
  }
  skip_section();
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_sets() {
  const long at = line_no();
  if (auto e = need_dimension(at, "GTSP_SET_SECTION")) return e;
  if (m_ < 0) return error(at, "GTSP_SETS must be given before GTSP_SET_SECTION");
  sets_.assign(static_cast<std::size_t>(m_), {});
  sets_line_ = li_ > 0 ? lines_[li_ - 1].number : at;  // the GTSP_SET_SECTION line
  std::vector<char> given(static_cast<std::size_t>(m_), 0);
  std::vector<long long> owner(static_cast<std::size_t>(n_), 0);  // the set each node is in (1-based), 0: none yet
  for (long k = 0; k < m_; ++k) {
    long long id = 0;
    if (auto e = next_integer(id, "set id")) return e;
    if (id < 1 || id > m_) return error(line_no(), "set id " + std::to_string(id) + " outside 1.." + std::to_string(m_));
    if (given[static_cast<std::size_t>(id - 1)]) return error(line_no(), "set " + std::to_string(id) + " given twice");
    given[static_cast<std::size_t>(id - 1)] = 1;
    while (true) {
      long long v = 0;
      if (auto e = next_integer(v, "node id or -1 ending the set")) return e;
      if (v == -1) break;
      if (v < 1 || v > n_) return error(line_no(), "set " + std::to_string(id) + " names node " + std::to_string(v) + " outside 1.." + std::to_string(n_));
      long long& o = owner[static_cast<std::size_t>(v - 1)];
      if (o == id) return error(line_no(), "set " + std::to_string(id) + " names node " + std::to_string(v) + " twice");
      if (o != 0) return error(line_no(), "node " + std::to_string(v) + " is in set " + std::to_string(o) + " and in set " + std::to_string(id));
      o = id;
      sets_[static_cast<std::size_t>(id - 1)].push_back(NodeId(static_cast<int>(v - 1)));
    }
    if (sets_[static_cast<std::size_t>(id - 1)].empty()) return error(line_no(), "set " + std::to_string(id) + " is empty");
  }
  for (long v = 0; v < n_; ++v)
    if (owner[static_cast<std::size_t>(v)] == 0) return error(sets_line_, "node " + std::to_string(v + 1) + " is in no set of GTSP_SET_SECTION");
  have_sets_ = true;
  skip_section();
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_ordering() {
  // Lines "A B1 B2 ... -1": set A before every B_i.
  while (li_ < lines_.size() && !is_keyword_line(lines_[li_])) {
    const Line& l = lines_[li_++];
    const auto tokens = words(l.text);
    if (tokens.empty()) continue;
    std::vector<long long> v;
    for (auto tok : tokens) {
      long long x = 0;
      const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), x);
      if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
        return error(l.number, "GTSP_SET_ORDERING: expected set ids, got '" + std::string(tok) + "'");
      v.push_back(x);
    }
    if (v.back() == -1) v.pop_back();
    if (v.size() < 2) return error(l.number, "GTSP_SET_ORDERING: a line needs a set and at least one successor");
    for (long long x : v)
      if (x < 1 || x > (m_ > 0 ? m_ : kMaxDimension))
        return error(l.number, "GTSP_SET_ORDERING: set id " + std::to_string(x) + " does not exist");
    for (std::size_t k = 1; k < v.size(); ++k) {
      order_.emplace_back(ClusterId(static_cast<int>(v[0] - 1)), ClusterId(static_cast<int>(v[k] - 1)));
      order_lines_.push_back(l.number);
    }
  }
  ci_ = 0;
  return std::nullopt;
}

std::optional<Diagnostic> Parser::parse_start_group() {
  long long g = 0;
  start_group_line_ = line_no();
  if (auto e = next_integer(g, "start group")) return e;
  start_group_ = static_cast<long>(g);
  skip_section();
  return std::nullopt;
}

Result<Instance> Parser::run() {
  while (li_ < lines_.size()) {
    const Line& l = lines_[li_];
    const auto first = first_word(l);
    if (first.empty()) {
      ++li_;
      continue;
    }
    if (!is_keyword_line(l)) return error(l.number, "number outside of any section: '" + std::string(first) + "'");
    std::string key(first);
    if (const auto c = key.find(':'); c != std::string::npos) key.resize(c);
    if (key == "EOF") break;
    if (key == "TYPE") {
      (void)parse_header_line(l);
      const std::string& t = type_;
      std::optional<InstanceFormat> said;
      if (t.rfind("PCGLNS", 0) == 0 || t.rfind("PCGTSP", 0) == 0) said = InstanceFormat::pcglns;
      else if (t.rfind("SOP", 0) == 0) said = InstanceFormat::sop;
      else if (t.rfind("GTSP", 0) == 0 || t.rfind("AGTSP", 0) == 0) said = InstanceFormat::gtsp;
      else if (!format_) return error(l.number, "unknown TYPE '" + t + "' (expected GTSP, AGTSP, SOP or PCGLNS)");
      // An SOP read as a GTSP would lose its precedences (its -1 entries refused or read as arcs).
      if (format_ && said && *said != *format_)
        return error(l.number, "TYPE is " + t + ", but the file is read as ." + to_string(*format_) +
                                   " (its name): rename it (.gtsp, .sop, .pcglns) to match its TYPE");
      if (!format_) format_ = said;
    }
    ++li_;
    ci_ = 0;
    std::optional<Diagnostic> e;
    if (key == "NODE_COORD_SECTION") e = parse_coords();
    else if (key == "EDGE_WEIGHT_SECTION") {
      if (!format_) return error(l.number, "TYPE must be given before EDGE_WEIGHT_SECTION");
      e = parse_weights();
    } else if (key == "GTSP_SET_SECTION") e = parse_sets();
    else if (key == "GTSP_SET_ORDERING") e = parse_ordering();
    else if (key == "START_GROUP_SECTION") e = parse_start_group();
    else if (key.size() > 8 && key.compare(key.size() - 8, 8, "_SECTION") == 0) skip_section();  // DISPLAY_DATA_SECTION ...
    else e = parse_header_line(l);
    if (e) return *e;
  }
  return finish();
}

// Precedence pairs (a before b, 0-based) as the file gives them: no pair on one set, none ending at
// the start, no cycle; each error at the line of a pair concerned, with the file's 1-based ids.
std::optional<Diagnostic> Parser::check_orders(const std::vector<std::pair<ClusterId, ClusterId>>& pairs, const std::vector<long>& lines,
                                               const char* what) const {
  const bool sop = format_ == InstanceFormat::sop;
  const std::string unit = sop ? "node " : "set ";
  auto id = [](ClusterId c) { return std::to_string(c.value() + 1); };
  const auto m = static_cast<std::size_t>(m_);
  const ClusterId start(sop ? 0 : static_cast<int>(start_group_ - 1));
  std::vector<std::vector<std::size_t>> out(m);  // pair indices by their first set
  std::vector<int> indeg(m, 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [a, b] = pairs[k];
    if (a == b) return error(lines[k], std::string(what) + ": " + unit + id(a) + " must come before itself");
    if (b == start)
      return error(lines[k], std::string(what) + ": " + unit + id(a) + " must come before " + unit + id(b) + ", which " +
                                 (sop ? "starts the path" : "is the start set (START_GROUP_SECTION)"));
    if (sop && a.value() + 1 == n_)
      return error(lines[k], std::string(what) + ": node " + id(a) + " must come before node " + id(b) + ", but node " + id(a) +
                                 " ends the path");
    out[a.index()].push_back(k);
    ++indeg[b.index()];
  }
  std::vector<std::size_t> ready;
  for (std::size_t c = 0; c < m; ++c)
    if (indeg[c] == 0) ready.push_back(c);
  for (std::size_t r = 0; r < ready.size(); ++r)
    for (std::size_t k : out[ready[r]])
      if (--indeg[pairs[k].second.index()] == 0) ready.push_back(pairs[k].second.index());
  if (ready.size() == m) return std::nullopt;
  // A cycle: from a set left with predecessors, step back through pairs whose first set is left
  // too until a set repeats.
  std::vector<std::vector<std::size_t>> in(m);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (indeg[pairs[k].first.index()] > 0 && indeg[pairs[k].second.index()] > 0) in[pairs[k].second.index()].push_back(k);
  std::size_t c = 0;
  while (indeg[c] == 0) ++c;
  std::vector<int> seen(m, -1);
  std::vector<std::size_t> steps;
  while (seen[c] < 0) {
    seen[c] = static_cast<int>(steps.size());
    const std::size_t k = in[c].front();
    steps.push_back(k);
    c = pairs[k].first.index();
  }
  std::string cycle;
  for (std::size_t s = steps.size(); s-- > static_cast<std::size_t>(seen[c]);)
    cycle += unit + id(pairs[steps[s]].first) + " before ";
  cycle += unit + id(pairs[steps[static_cast<std::size_t>(seen[c])]].second);
  return error(lines[steps[static_cast<std::size_t>(seen[c])]], std::string(what) + ": the order has a cycle: " + cycle);
}

Result<Instance> Parser::finish() {
  const long last = lines_.empty() ? 1 : lines_.back().number;
  if (!format_) return error(last, "no TYPE and no known extension (.gtsp, .sop, .pcglns): cannot tell the format");
  if (n_ < 0) return error(last, "DIMENSION is missing");
  const InstanceFormat fmt = *format_;
  if (fmt == InstanceFormat::sop) {
    m_ = n_;
    sets_.clear();
    for (long k = 0; k < n_; ++k) sets_.push_back({NodeId(static_cast<int>(k))});
    have_sets_ = true;
  }
  if (!have_sets_) return error(last, "GTSP_SET_SECTION is missing");
  std::optional<detail::Metric> metric;
  if (weight_type_.empty()) return error(last, "EDGE_WEIGHT_TYPE is missing");
  if (weight_type_ == "EXPLICIT") {
    if (!have_weights_) return error(last, "EDGE_WEIGHT_TYPE is EXPLICIT but EDGE_WEIGHT_SECTION is missing");
  } else {
    metric = detail::parse_metric(weight_type_);
    if (!metric) return error(weight_type_line_, "unsupported EDGE_WEIGHT_TYPE '" + weight_type_ + "'");
    if (!have_coords_) return error(last, "EDGE_WEIGHT_TYPE " + weight_type_ + " needs NODE_COORD_SECTION");
    if (fmt != InstanceFormat::gtsp && fmt != InstanceFormat::pcglns) return error(weight_type_line_, "SOP instances must be EXPLICIT");
  }

  solve::ProblemBuilder b(static_cast<int>(n_));
  b.set_name(name_);
  for (auto& s : sets_) b.add_cluster(s);
  if (metric == detail::Metric::euc_2d && n_ > kMaxMatrixNodes) {
    // Planar costs compute nint(distance) inline, as EUC_2D defines it (scale 1, no base): several
    // times faster than the callback below.
    solve::PlanarCosts pc;
    pc.per_unit = 1.0;
    for (const detail::Coord& q : coords_) pc.out.push_back({q.x, q.y});
    pc.in = pc.out;
    b.set_planar_costs(std::move(pc));
  } else if (metric && n_ > kMaxMatrixNodes) {
    auto coords = std::make_shared<const std::vector<detail::Coord>>(std::move(coords_));
    const detail::Metric mt = *metric;
    b.set_cost_function([coords, mt](NodeId a, NodeId c) { return detail::tsplib_distance(mt, (*coords)[a.index()], (*coords)[c.index()]); },
                        true);
  } else if (metric) {
    const auto n = static_cast<std::size_t>(n_);
    matrix_.assign(n * n, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        if (i != j) matrix_[i * n + j] = detail::tsplib_distance(*metric, coords_[i], coords_[j]);
    b.set_cost_matrix(std::move(matrix_));
  } else {
    const auto n = static_cast<std::size_t>(n_);
    if (fmt == InstanceFormat::sop) {
      // c[i][j] == -1: j before i; the arc i -> j stays forbidden (read as kForbiddenCost).
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          if (i != j && matrix_[i * n + j] == solve::kForbiddenCost)
            b.add_precedence(ClusterId(static_cast<int>(j)), ClusterId(static_cast<int>(i)));
      // A path from node 1 to node n: every other node before n.
      for (std::size_t k = 1; k + 1 < n; ++k) b.add_precedence(ClusterId(static_cast<int>(k)), ClusterId(static_cast<int>(n - 1)));
    }
    for (std::size_t i = 0; i < n; ++i) matrix_[i * n + i] = 0;  // never used; GTSPLIB puts 9999 or 1e8 there
    b.set_cost_matrix(std::move(matrix_));
  }
  if (fmt == InstanceFormat::sop) {
    b.set_kind(solve::RouteKind::open_path);
    b.set_start_cluster(ClusterId(0));
    std::vector<std::pair<ClusterId, ClusterId>> pairs;
    std::vector<long> lines;
    for (const MinusOne& e : minus_ones_) {
      pairs.emplace_back(ClusterId(static_cast<int>(e.j)), ClusterId(static_cast<int>(e.i)));
      lines.push_back(e.line);
    }
    if (auto e = check_orders(pairs, lines, "EDGE_WEIGHT_SECTION (-1: the column's node before the row's)")) return *e;
  } else {
    b.set_kind(solve::RouteKind::closed_tour);
    if (start_group_ < 1 || start_group_ > m_) return error(start_group_line_, "START_GROUP_SECTION names set " + std::to_string(start_group_) + ", there are " + std::to_string(m_));
    b.set_start_cluster(ClusterId(static_cast<int>(start_group_ - 1)));
    for (std::size_t k = 0; k < order_.size(); ++k) {
      // The section may come before GTSP_SETS, so its ids are checked against it only here.
      const auto [a, c] = order_[k];
      if (std::max(a.value(), c.value()) >= m_)
        return error(order_lines_[k], "GTSP_SET_ORDERING: set id " + std::to_string(std::max(a.value(), c.value()) + 1) +
                                          " does not exist (GTSP_SETS is " + std::to_string(m_) + ")");
    }
    if (auto e = check_orders(order_, order_lines_, "GTSP_SET_ORDERING")) return *e;
    for (const auto& [a, c] : order_) b.add_precedence(a, c);
  }
  // The search prices a forbidden arc at kForbiddenCost (2^41): a route of m arcs of the largest
  // weight must cost less, or a route through a forbidden arc would look the cheaper one.
  if (!minus_ones_.empty() && m_ > 0 && max_weight_ > (solve::kForbiddenCost - 1) / m_)
    return error(max_weight_line_, "edge weight " + std::to_string(max_weight_) + " is too large next to the -1 entries: with " +
                                       std::to_string(m_) + " sets a route could cost more than a forbidden arc is priced (2^41); "
                                       "weights up to " + std::to_string((solve::kForbiddenCost - 1) / m_) + " are supported (scale them down)");
  if (m_ != static_cast<long>(sets_.size())) return error(last, "GTSP_SETS does not match the sets given");
  auto built = b.build();
  if (!built) {
    Diagnostic d = built.error();
    d.file = file_;
    return d;
  }
  Instance inst;
  inst.name = name_;
  inst.format = fmt;
  inst.problem = std::move(built).value();
  return inst;
}

std::optional<InstanceFormat> format_from_extension(const std::string& file) {
  auto ends = [&](std::string_view ext) {
    if (file.size() < ext.size()) return false;
    for (std::size_t k = 0; k < ext.size(); ++k)
      if (std::tolower(static_cast<unsigned char>(file[file.size() - ext.size() + k])) != ext[k]) return false;
    return true;
  };
  if (ends(".gtsp")) return InstanceFormat::gtsp;
  if (ends(".sop")) return InstanceFormat::sop;
  if (ends(".pcglns") || ends(".pcgtsp")) return InstanceFormat::pcglns;
  return std::nullopt;
}

}  // namespace

Result<Instance> parse_instance(std::string_view text, const std::string& file, std::optional<InstanceFormat> format) {
  if (!format) format = format_from_extension(file);
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // a UTF-8 byte order mark (Windows editors)
  Parser parser(text, file, format);
  auto r = parser.run();
  if (r && r->name.empty()) {
    auto slash = file.find_last_of('/');
    r->name = file.substr(slash == std::string::npos ? 0 : slash + 1);
  }
  return r;
}

Result<Instance> read_instance(const std::string& path) {
  auto text = read_file(path);
  if (!text) return text.error();
  return parse_instance(*text, path);
}

}  // namespace cutroute::io
