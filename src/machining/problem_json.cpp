#include <cutroute/machining/problem_json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include <cutroute/core/json_text.hpp>

#include <cutroute/machining/optimize.hpp>

namespace cutroute::machining {

namespace {

using nlohmann::json;

// Thrown inside the reader only; turned into one Diagnostic at the boundary.
struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A JSON object with its path; reads typed fields, remembers which keys were used so that unknown
// (misspelt) keys are reported instead of silently ignored.
class Obj {
 public:
  Obj(const json& j, std::string path) : j_(j), path_(std::move(path)) {
    if (!j_.is_object()) throw FieldError(where() + ": expected an object");
  }
  ~Obj() = default;
  Obj(const Obj&) = delete;
  Obj& operator=(const Obj&) = delete;

  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  std::string where() const { return path_.empty() ? "(top level)" : path_; }
  bool has(const std::string& key) {
    used_.insert(key);
    return j_.contains(key) && !j_.at(key).is_null();
  }
  const json& raw(const std::string& key) {
    if (!has(key)) throw FieldError(at(key) + ": missing required field");
    return j_.at(key);
  }
  double num(const std::string& key) { return as_number(raw(key), at(key)); }
  double num(const std::string& key, double def) { return has(key) ? num(key) : def; }
  std::optional<double> opt_num(const std::string& key) {
    return has(key) ? std::optional<double>(num(key)) : std::nullopt;
  }
  int integer(const std::string& key, int def) {
    if (!has(key)) return def;
    const json& v = j_.at(key);
    if (!v.is_number_integer()) throw FieldError(at(key) + ": expected an integer");
    const auto x = v.get<long long>();
    if (x < -1000000 || x > 1000000) throw FieldError(at(key) + ": integer out of range");
    return static_cast<int>(x);
  }
  bool boolean(const std::string& key, bool def) {
    if (!has(key)) return def;
    if (!j_.at(key).is_boolean()) throw FieldError(at(key) + ": expected true or false");
    return j_.at(key).get<bool>();
  }
  std::string str(const std::string& key) {
    const json& v = raw(key);
    if (!v.is_string()) throw FieldError(at(key) + ": expected a string");
    return v.get<std::string>();
  }
  std::string str(const std::string& key, const std::string& def) { return has(key) ? str(key) : def; }
  std::vector<double> numbers(const std::string& key, std::size_t exact = 0) {
    const json& v = raw(key);
    if (!v.is_array()) throw FieldError(at(key) + ": expected an array of numbers");
    if (exact && v.size() != exact) {
      throw FieldError(at(key) + ": expected " + std::to_string(exact) + " numbers, got " +
                       std::to_string(v.size()));
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out.push_back(as_number(v[i], at(key) + "[" + std::to_string(i) + "]"));
    return out;
  }
  // Keys the reader never asked for are typos or unsupported options; "_..." and the notes are free.
  void finish() const {
    for (auto it = j_.begin(); it != j_.end(); ++it) {
      const std::string& k = it.key();
      if (used_.count(k) || k.empty() || k[0] == '_' || k == "comment" || k == "source" || k == "notes")
        continue;
      throw FieldError(at(k) + ": unknown field");
    }
  }

  static double as_number(const json& v, const std::string& path) {
    if (!v.is_number()) throw FieldError(path + ": expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) throw FieldError(path + ": expected a finite number");
    return x;
  }

 private:
  const json& j_;
  std::string path_;
  std::set<std::string> used_;
};

template <class E>
E pick(const std::string& path, const std::string& value,
       std::initializer_list<std::pair<const char*, E>> names) {
  std::string known;
  for (const auto& [n, e] : names) {
    if (value == n) return e;
    known += known.empty() ? std::string("'") + n + "'" : std::string(", '") + n + "'";
  }
  throw FieldError(path + ": unknown model name '" + value + "' (expected one of " + known + ")");
}

ForceModel read_force(Obj& parent, const std::string& key, bool radial) {
  Obj o(parent.raw(key), parent.at(key));
  ForceModel m;
  // Two separate lists: an initializer_list's array would not outlive a conditional expression.
  const std::string model = o.str("model");
  m.kind = radial ? pick<ForceKind>(o.at("model"), model,
                                    {{"handbook", ForceKind::handbook}, {"ratio", ForceKind::ratio}})
                  : pick<ForceKind>(o.at("model"), model,
                                    {{"handbook", ForceKind::handbook}, {"kienzle", ForceKind::kienzle}});
  switch (m.kind) {
    case ForceKind::handbook:
      m.handbook.Cp = o.num("Cp");
      m.handbook.x = o.num("x");
      m.handbook.y = o.num("y");
      m.handbook.n = o.num("n");
      m.handbook.Kp = o.num("Kp", 1.0);
      break;
    case ForceKind::kienzle:
      m.kienzle.kc11 = o.num("kc11");
      m.kienzle.mc = o.num("mc");
      break;
    case ForceKind::ratio:
      m.k_r = o.num("k_r");
      break;
  }
  o.finish();
  return m;
}

HandbookLife read_life_set(const json& j, const std::string& path) {
  Obj o(j, path);
  HandbookLife h;
  h.Cv = o.num("Cv");
  h.Kv = o.num("Kv", 1.0);
  h.m = o.num("m");
  h.x = o.num("x");
  h.y = o.num("y");
  if (o.has("f_range")) {
    const auto r = o.numbers("f_range", 2);
    h.f_lo = r[0];
    h.f_hi = r[1];
  } else {
    h.f_lo = 0.0;
    h.f_hi = std::numeric_limits<double>::infinity();
  }
  o.finish();
  return h;
}

Problem read(const json& root) {
  Problem p;
  Obj top(root, "");
  p.name = top.str("name", "");
  {
    Obj o(top.raw("operation"), "operation");
    p.op.D = o.num("D");
    p.op.L = o.num("L");
    p.op.l_extra = o.num("l_extra", 3.0);
    p.op.passes = o.integer("passes", 1);
    if (o.has("ap")) {
      p.op.ap = o.num("ap");
    } else if (o.has("D_pre")) {
      // ap = (D − D_pre)/2 per pass
      p.op.ap = (p.op.D - o.num("D_pre")) / (2.0 * std::max(1, p.op.passes));
    } else {
      throw FieldError("operation.ap: missing required field (or give operation.D_pre)");
    }
    o.finish();
  }
  {
    Obj o(top.raw("tool"), "tool");
    p.tool.r_eps = o.num("r_eps");
    p.tool.kappa_r = o.num("kappa_r", 90.0);
    p.tool.C_edge = o.num("C_edge");
    p.tool.t_change = o.num("t_change");
    p.tool.F_allow = o.opt_num("F_allow");
    o.finish();
  }
  {
    Obj o(top.raw("tool_life"), "tool_life");
    p.life.kind =
        pick<ToolLifeKind>(o.at("model"), o.str("model"),
                           {{"taylor", ToolLifeKind::taylor}, {"handbook", ToolLifeKind::handbook}});
    p.life.source = o.str("source", "");
    if (p.life.kind == ToolLifeKind::taylor) {
      p.life.taylor.C = o.num("C");
      p.life.taylor.n = o.num("n");
    } else {
      const json& sets = o.raw("sets");
      if (!sets.is_array()) throw FieldError("tool_life.sets: expected an array of coefficient sets");
      for (std::size_t i = 0; i < sets.size(); ++i) {
        p.life.sets.push_back(read_life_set(sets[i], "tool_life.sets[" + std::to_string(i) + "]"));
      }
    }
    if (o.has("warn_window")) {
      const auto w = o.numbers("warn_window", 2);
      p.life.warn_T_min = w[0];
      p.life.warn_T_max = w[1];
    }
    o.finish();
  }
  {
    Obj o(top.raw("force"), "force");
    p.tangential = read_force(o, "tangential", false);
    if (o.has("radial")) p.radial = read_force(o, "radial", true);
    o.finish();
  }
  {
    Obj o(top.raw("machine"), "machine");
    p.machine.P_motor = o.num("P_motor");
    p.machine.eta = o.num("eta");
    p.machine.n_max = o.num("n_max");
    p.machine.Vf_max = o.num("Vf_max");
    p.machine.n_base = o.num("n_base", 0.0);
    if (o.has("spindle_steps")) p.machine.spindle_steps = o.numbers("spindle_steps");
    o.finish();
  }
  {
    Obj o(top.raw("rates"), "rates");
    p.econ.rates.R_AO = o.num("R_AO");
    p.econ.rates.R_Z = o.num("R_Z");
    p.econ.rates.R_Erx = o.num("R_Erx");
    p.econ.rates.R_Exx = o.num("R_Exx");
    p.econ.rates.R_TR = o.num("R_TR");
    p.econ.t_load = o.num("t_load");
    p.econ.R_H = o.num("R_H");
    p.econ.rate_map =
        pick<RateMap>(o.at("rate_map"), o.str("rate_map", "physical"),
                      {{"physical", RateMap::physical}, {"listed_order", RateMap::listed_order}});
    o.finish();
  }
  {
    Obj o(top.raw("quality"), "quality");
    p.quality.Ra_max = o.num("Ra_max");
    p.quality.k_Ra = o.num("k_Ra", 1.0);
    o.finish();
  }
  if (top.has("accuracy")) {
    Obj o(top.raw("accuracy"), "accuracy");
    Accuracy a;
    {
      Obj b(o.raw("bar"), "accuracy.bar");
      a.bar.E = b.num("E");
      a.bar.d = b.num("d");
      a.bar.d_in = b.num("d_in", 0.0);
      a.bar.mode = pick<OverhangMode>(b.at("overhang_mode"), b.str("overhang_mode", "constant"),
                                      {{"constant", OverhangMode::constant}, {"quill", OverhangMode::quill}});
      if (a.bar.mode == OverhangMode::constant)
        a.bar.L_o = b.num("L_o");
      else
        a.bar.L_o0 = b.num("L_o0");
      b.finish();
    }
    {
      Obj b(o.raw("blank"), "accuracy.blank");
      a.TA = b.num("TA");
      a.TB = b.num("TB");
      a.T_R3 = b.num("T_R3");
      b.finish();
    }
    a.waves = o.integer("waves", 1);
    a.P = o.num("P", 0.9973);
    a.K_TZ = o.num("K_TZ");
    a.compensate_static_deflection = o.boolean("compensate_static_deflection", true);
    a.delta_allow = o.opt_num("delta_allow");
    if (o.has("integration")) {
      Obj in(o.raw("integration"), "accuracy.integration");
      a.n_phi = in.integer("n_phi", 36);
      a.n_z = in.integer("n_z", a.bar.mode == OverhangMode::quill ? 11 : 1);
      a.cubature.m = in.integer("simpson_m", 64);
      a.cubature.n = in.integer("simpson_n", 64);
      in.finish();
    } else if (a.bar.mode == OverhangMode::quill) {
      a.n_z = 11;  // L_o varies along z: sample the bore at 11 sections
    }
    if (o.has("K_TZ_sweep")) p.K_TZ_sweep = o.numbers("K_TZ_sweep");
    o.finish();
    p.accuracy = a;
  }
  {
    Obj o(top.raw("search"), "search");
    p.search.vc_min = o.num("vc_min");
    p.search.vc_max = o.num("vc_max");
    p.search.f_min = o.num("f_min");
    p.search.f_max = o.num("f_max");
    if (o.has("grid")) {
      const json& g = o.raw("grid");
      if (!g.is_array() || g.size() != 2 || !g[0].is_number_integer() || !g[1].is_number_integer()) {
        throw FieldError("search.grid: expected [n_vc, n_f] integers");
      }
      const auto gv = g[0].get<long long>(), gf = g[1].get<long long>();
      if (gv < 3 || gv > 4001 || gf < 3 || gf > 4001)
        throw FieldError("search.grid: each size must lie in [3, 4001]");
      p.search.grid_vc = static_cast<int>(gv);
      p.search.grid_f = static_cast<int>(gf);
    }
    if (o.has("T_window")) {
      const auto w = o.numbers("T_window", 2);
      p.search.T_min = w[0];
      p.search.T_max = w[1];
    }
    o.finish();
  }
  top.finish();
  return p;
}

}  // namespace

namespace {

constexpr std::string_view kMissing = ": missing required field";

// The JSON pointer of a field path as the reader names it ("tool_life.sets[0].Cv").
json::json_pointer pointer_of(const std::string& path) {
  std::string out;
  std::size_t at = 0;
  while (at < path.size()) {
    const std::size_t dot = path.find('.', at);
    std::string part = path.substr(at, dot == std::string::npos ? std::string::npos : dot - at);
    std::string index;
    if (const std::size_t b = part.find('['); b != std::string::npos && part.back() == ']') {
      index = part.substr(b + 1, part.size() - b - 2);
      part.resize(b);
    }
    out += "/" + part;
    if (!index.empty()) out += "/" + index;
    if (dot == std::string::npos) break;
    at = dot + 1;
  }
  return json::json_pointer(out);
}

// The other required fields missing after `first` (the reader stops at the first): each missing
// one is filled in a copy with a stand-in (a number, else an object or a string, as the reader
// asks) and the copy read again, so that one message names every field to add. Stops at any
// other error, which the fields given already cause or the stand-in does.
std::vector<std::string> more_missing(const json& root, std::string first) {
  std::vector<std::string> out;
  json copy = root;
  for (int round = 0; round < 64; ++round) {
    const std::size_t cut = first.find(kMissing);  // "operation.ap: missing required field (or give ...)"
    if (cut == std::string::npos || cut == 0) break;
    const std::string path = first.substr(0, cut);
    if (round > 0) out.push_back(path);
    bool read_past = false;
    for (const json& stand_in : {json(1.0), json::object(), json("x")}) {
      try {
        copy[pointer_of(path)] = stand_in;
      } catch (const json::exception&) {
        return out;
      }
      try {
        (void)read(copy);
        return out;
      } catch (const FieldError& e) {
        const std::string what = e.what();
        if (what.rfind(path + ":", 0) == 0 && what.find(kMissing) == std::string::npos) continue;  // another stand-in
        first = what;
        read_past = true;
      } catch (const json::exception&) {
        return out;
      }
      break;
    }
    if (!read_past) break;
  }
  return out;
}

// One problem object (already parsed) -> Problem, with `prefix` in front of every path.
Result<Problem> read_one(const json& root, const std::string& file, const std::string& prefix) {
  try {
    Problem p = read(root);
    const auto problems = validate(p);
    if (!problems.empty()) {
      std::string msg = prefix + problems.front();
      if (problems.size() > 1) {
        msg += " (and " + std::to_string(problems.size() - 1) + " more: " + prefix + problems[1] +
               (problems.size() > 2 ? ", ..." : "") + ")";
      }
      return make_error(msg, file);
    }
    return p;
  } catch (const FieldError& e) {
    std::string msg = prefix + e.what();
    const auto more = more_missing(root, e.what());
    if (!more.empty()) {
      msg += " (and " + std::to_string(more.size()) + " more:";
      for (std::size_t i = 0; i < more.size(); ++i) msg += (i ? ", " : " ") + prefix + more[i];
      msg += ")";
    }
    return make_error(msg, file);
  } catch (const json::exception& e) {
    return make_error(prefix + "invalid problem: " + e.what(), file);
  }
}

Result<json> parse(std::string_view text, const std::string& file) {
  auto j = parse_json_text(text, file);
  if (!j) return j.error();
  if (const auto key = duplicate_json_key(text)) return make_error("key \"" + *key + "\" appears twice in one object", file);
  return j;
}

}  // namespace

Result<Transitions> read_transitions_json(std::string_view text, const std::string& file) {
  auto root = parse(text, file);
  if (!root) return root.error();
  Transitions t;
  if (root->is_object() && root->contains("transitions")) {
    t.is_list = true;
    try {
      Obj top(*root, "");
      t.name = top.str("name", "");
      const json& list = top.raw("transitions");
      if (!list.is_array() || list.empty())
        throw FieldError("transitions: expected a non-empty array of problems");
      top.finish();
      for (std::size_t i = 0; i < list.size(); ++i) {
        auto p = read_one(list[i], file, "transitions[" + std::to_string(i) + "].");
        if (!p) return p.error();
        t.items.push_back(std::move(p).value());
      }
    } catch (const FieldError& e) {
      return make_error(e.what(), file);
    }
    return t;
  }
  auto p = read_one(*root, file, "");
  if (!p) return p.error();
  t.name = p->name;
  t.items.push_back(std::move(p).value());
  return t;
}

Result<Problem> read_problem_json(std::string_view text, const std::string& file) {
  auto root = parse(text, file);
  if (!root) return root.error();
  return read_one(*root, file, "");
}

}  // namespace cutroute::machining
