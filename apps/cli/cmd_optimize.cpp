// cutroute optimize: DXF nest(s) -> optimized cutting program, report, pictures (in parallel for several nests).
#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <set>
#include <thread>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/io/batch_summary.hpp>
#include <cutroute/io/output_file.hpp>
#include <cutroute/io/route_picture.hpp>
#include <cutroute/pipeline/optimize.hpp>

#include "commands.hpp"
#include "input_options.hpp"
#include "progress_line.hpp"

namespace cutroute::cli {
namespace {

struct Opts {
  std::vector<std::string> nests;
  std::string out;
  std::string report, svg, html;
  std::string material;
  double thickness = 0;
  std::string machine;
  bool interpolate = false;
  std::string objective = "time";
  double time_limit = 10;
  double work_limit_m = 0;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string solver = "auto";
  std::string start;
  double kerf = -1;
  std::string kerf_mode = "controller";
  bool keep_compensation = false;
  std::string dialect;  // empty: the machine profile's
  double entry_step = 0;
  bool quiet = false;
  bool allow_crossing = false;
  bool allow_kerf_overlap = false;
  std::string technique = "auto";
  double chain_gap = 20;
  bool multi_segment = false;
  model::MultiSegmentOptions multi;
  InputOptions input;
  pipeline::ShopRules rules;  // shop rules (docs/SHOP-RULES.md)
  std::string sheet_clamp;
  std::string tab_lead_in = "auto";
};

struct Outputs {
  std::string program, report, svg, html;
};


// The pipeline's options from the command line; a malformed --start is a usage error.
Result<pipeline::OptimizeOptions> optimize_options(const Opts& o) {
  pipeline::OptimizeOptions po;
  po.machine_file = o.machine;
  po.material = o.material;
  if (o.thickness > 0) po.thickness_mm = o.thickness;
  po.interpolate = o.interpolate;
  po.objective = o.objective == "cost" ? cost::Objective::cost : cost::Objective::time;
  po.time_limit_s = o.time_limit;
  po.work_limit = o.work_limit_m * 1e6;
  po.seed = o.seed;
  po.solver = o.solver == "exact" ? solve::SolverKind::exact
              : o.solver == "heuristic" ? solve::SolverKind::heuristic : solve::SolverKind::automatic;
  if (!o.start.empty()) {
    auto p = parse_point(o.start, "--start");
    if (!p) return p.error();
    po.start = *p;
  }
  if (o.kerf >= 0) po.kerf_mm = o.kerf;
  po.kerf_mode = o.kerf_mode == "none"  ? nc::KerfMode::none
                 : o.kerf_mode == "cam" ? nc::KerfMode::cam
                                        : nc::KerfMode::controller;
  po.allow_kerf_overlap = o.allow_kerf_overlap;
  po.offset_refused_cuts = !o.keep_compensation;
  po.dialect = o.dialect;
  po.entry_step_mm = o.entry_step;
  po.allow_crossing = o.allow_crossing;
  po.technique = o.technique == "standard" ? pipeline::Technique::standard
                 : o.technique == "chain"  ? pipeline::Technique::chain
                 : o.technique == "common" ? pipeline::Technique::common
                 : o.technique == "multi"  ? pipeline::Technique::multi
                                           : pipeline::Technique::automatic;
  po.chain.max_gap_mm = o.chain_gap;
  po.multi_segment = o.multi_segment;
  po.multi = o.multi;
  po.rules = o.rules;  // shop rules
  if (!o.sheet_clamp.empty()) po.rules.sheet_clamp = pipeline::parse_clamp_side(o.sheet_clamp);
  po.rules.tab_lead_in = pipeline::parse_tab_lead_in(o.tab_lead_in).value_or(pipeline::TabLeadIn::automatic);
  return po;
}

// Each nest's output files. One nest: -o is the program file; several: -o is a folder for all outputs.
Result<std::vector<Outputs>> output_paths(const Opts& o) {
  const bool batch = o.nests.size() > 1;
  if (batch && (o.out.empty() || o.out == "-")) return make_error("several nests need -o DIR for their outputs (not stdout)");
  if (batch && (!o.report.empty() || !o.svg.empty() || !o.html.empty()))
    return make_error("with several nests, every output goes to -o DIR (program, .json report, .svg, .html); "
                      "--report/--svg/--html name files of a single nest");
  std::vector<Outputs> outs(o.nests.size());
  std::set<std::string> stems;  // batch: each nest's outputs under a name of its own
  for (std::size_t i = 0; i < o.nests.size(); ++i) {
    std::string stem = std::filesystem::path(o.nests[i]).stem().string();
    if (batch) {
      // Sheets of the same name from different folders (job1/sheet.dxf, job2/sheet.dxf) get
      // sheet.ngc, sheet-2.ngc, ... in the order given; summary.csv says which is which.
      for (int k = 2; !stems.insert(stem).second; ++k) stem = std::filesystem::path(o.nests[i]).stem().string() + "-" + std::to_string(k);
      const auto base = (std::filesystem::path(o.out) / stem).string();  // the folder is made by run()
      outs[i] = {base + ".ngc", base + ".json", base + ".svg", base + ".html"};
      continue;
    }
    outs[i] = {o.out.empty() ? stem + ".ngc" : o.out, o.report, o.svg, o.html};
    // Two outputs into one file (or both to stdout) would leave only the last, or a mix.
    const std::vector<std::pair<const char*, std::string>> named = {
        {"-o", outs[i].program}, {"--report", o.report}, {"--svg", o.svg}, {"--html", o.html}};
    for (std::size_t a = 0; a < named.size(); ++a)
      for (std::size_t b = a + 1; b < named.size(); ++b)
        if (!named[a].second.empty() && !named[b].second.empty() && io::same_output(named[a].second, named[b].second))
          return make_error(std::string(named[a].first) + " and " + named[b].first + " name the same output: " + named[b].second);
  }
  // An output never replaces a drawing being read (a slip of -o nest.dxf lost the drawing).
  for (const auto& out : outs)
    for (const std::string* path : {&out.program, &out.report, &out.svg, &out.html})
      for (const auto& nest : o.nests)
        if (!path->empty() && io::same_output(*path, nest))
          return make_error("the output " + *path + " is the input drawing " + nest + ": an output never replaces its input");
  return outs;
}

// What became of one nest: its exit code, the line printed for it (summary or error), the warnings
// printed even with --quiet (the program is less safe or less sure to run than asked for), and its
// report when it was cut (for the batch summary).
struct NestOutcome {
  int code = kOk;
  std::string message, warnings;
  nlohmann::json report;
  bool not_started = false;  // Ctrl-C or SIGTERM came first: not cut, though nothing is wrong with it
};

// The warnings of a cut nest that reach stderr: rapids left over freed parts, cuts the controller's
// compensation may refuse, cuts after a tab that resume on the part's edge although lead-ins were
// asked for, parts or tabs that hold nothing, and the open contours not cut.
std::string printed_warnings(const std::string& nest, const std::vector<Diagnostic>& route, const io::LoadedNest& loaded,
                             const nlohmann::json& report) {
  const std::vector<Diagnostic>& loading = loaded.diagnostics;
  std::string out;
  for (Diagnostic d : route) {
    if (d.code != "tip_up.time_limit" && d.code != "refine.time_limit" && d.code != "technique.time_limit" && d.code != "run.interrupted" &&
        d.code != "kerf.controller_detail" && d.code != "kerf.offset_written" && d.code != "program.readback" && d.code != "nest.smaller_than_kerf" && d.code != "nest.kerf_loss" && d.code != "nest.closer_than_kerf" && d.code != "machine.work_area" &&
        d.code != "tabs.resumed_on_path" && d.code != "tabs.part_without_skeleton_edge" && d.code != "tabs.on_a_neighbours_cut")
      continue;
    if (d.file.empty()) d.file = nest;
    out += "cutroute: " + format(d) + "\n";
  }
  // A pierce on the contour marks the part's edge: one line for the written program's (the
  // chosen technique's entries, not every alternative's), naming the first few.
  if (report.contains("sequence")) {
    int on_edge = 0;
    std::string named;
    std::set<int> seen;  // a common-line outline may be entered on one contour twice
    for (const auto& e : report["sequence"])
      if (e.value("fallback", "") == "on_contour" && seen.insert(e.value("contour", 0)).second && on_edge++ < 5)
        named += (named.empty() ? "" : ", ") + ("part " + std::to_string(e.value("part", 0)) + " " + e.value("kind", "contour") + " (contour " +
                                                std::to_string(e.value("contour", 0)) + ")");
    if (on_edge > 0)
      out += "cutroute: " + format(make_warning(std::to_string(on_edge) + " contour(s) pierced on their edge, no lead-in fitting (" + named +
                                                    (on_edge > 5 ? ", ..." : "") + "): a mark on the part there",
                                                nest)) + "\n";
  }
  // A unit the drawing names but cutroute cannot read scales the whole program, a --sheet size
  // no border has leaves out another border or none, curves the CAD program hides are cut though
  // the drawing looked right without them, and a tilted plane is cut as seen from above: said always.
  for (Diagnostic d : loading) {
    if (d.code != "dxf.units_ignored" && d.code != "nest.sheet_size" && d.code != "dxf.hidden_layer" &&
        d.code != "dxf.invisible" && d.code != "dxf.tilted_plane")
      continue;
    if (d.file.empty()) d.file = nest;
    out += "cutroute: " + format(d) + "\n";
  }
  // What reading changed in the drawing: gaps closed (ends moved to meet), outlines drawn twice
  // (cut once), loops that enclose nothing (cut as a slit): one line for each kind, naming the first.
  const std::pair<const char*, const char*> changed[] = {
      {"chain.gap_closed", " gap(s) in the drawing closed, each end moved by half the gap (first: %); --close-gaps 0 leaves them open"},
      {"nest.duplicate", " contour(s) drawn twice, cut once (first: %)"},
      {"nest.no_area", " contour(s) enclosing no area, cut as a slit (first: %)"}};
  for (const auto& [code, text] : changed) {
    int count = 0;
    const Diagnostic* first = nullptr;
    for (const Diagnostic& d : loading) {
      if (d.code != code) continue;
      if (count++ == 0) first = &d;
    }
    if (first == nullptr) continue;
    Diagnostic d = *first;
    if (d.file.empty()) d.file = nest;
    const std::string pattern = text;
    const auto at = pattern.find('%');
    d.message = std::to_string(count) + pattern.substr(0, at) + d.message + pattern.substr(at + 1);
    out += "cutroute: " + format(d) + "\n";
  }
  // Open contours are not cut, and a part drawn with a gap would be missing from the program:
  // one line for them all (drawings with text or hatching have many), naming the first few places
  // with their layer. A block of text inserted once yields dozens from one INSERT line: each place
  // is named once, with its count (d2g_Frontplatte: "39 at line 6779, layer Schraffuren").
  constexpr std::size_t kNamed = 5;
  struct Place {
    std::string where;
    int count = 0;
  };
  std::vector<Place> places;
  int open = 0;
  bool more = false;
  // Those whose ends nearly meet (within 1 mm: a part drawn with a gap, most likely) are named
  // first, then the others in drawing order: marks and text strokes crowded the parts out of the
  // five places named.
  std::vector<const io::OpenPath*> order;
  for (const auto& p : loaded.open_paths)
    if (!p.path.vertices.empty()) order.push_back(&p);
  std::stable_partition(order.begin(), order.end(), [](const io::OpenPath* p) { return p->nearest_end_mm > 0; });
  for (const io::OpenPath* p : order) {
    ++open;
    std::string where = p->line ? "line " + std::to_string(*p->line) : "entity " + p->handle;
    if (!p->layer.empty()) where += ", layer " + p->layer;
    const auto it = std::find_if(places.begin(), places.end(), [&](const Place& q) { return q.where == where; });
    if (it != places.end()) ++it->count;
    else if (places.size() < kNamed) places.push_back({std::move(where), 1});
    else more = true;
  }
  if (open > 0) {
    // The narrowest gap among them, when a wider --close-gaps would close it.
    double narrowest = -1;
    for (const auto& p : loaded.open_paths)
      if (p.nearest_end_mm > 0 && (narrowest < 0 || p.nearest_end_mm < narrowest)) narrowest = p.nearest_end_mm;
    const std::string nearest = narrowest > 0 ? " (the nearest free ends lie " + format_fixed(narrowest, 3) + " mm apart: --close-gaps " +
                                                    format_fixed(io::gap_to_close(narrowest), 3) + " joins them)"
                                              : std::string();
    // Those inside a part's material may be its holes, drawn with a gap: the part is then cut whole.
    const auto inside = std::count_if(loaded.open_paths.begin(), loaded.open_paths.end(), [](const io::OpenPath& p) { return p.inside_part.has_value(); });
    std::string in_parts;
    if (inside > 0) {
      const auto first = std::find_if(loaded.open_paths.begin(), loaded.open_paths.end(), [](const io::OpenPath& p) { return p.inside_part.has_value(); });
      in_parts = ", and " + std::to_string(inside) + " lie in the material of a part (first: part " + std::to_string(first->inside_part->value() + 1) +
                 "), which is cut without them if they are holes drawn with a gap";
    }
    std::string named;
    for (const Place& p : places)
      named += (named.empty() ? "" : "; ") + (p.count > 1 ? std::to_string(p.count) + " at " : std::string()) + p.where;
    out += "cutroute: " + format(make_warning(std::to_string(open) + " open contour(s) not cut, their ends not meeting within " +
                                                  "--snap and --close-gaps (" + named + (more ? "; ..." : "") +
                                                  "): a part drawn with a gap among them is missing from the program" + in_parts + nearest,
                                              nest)) + "\n";
  }
  return out;
}

// The summary line of a cut nest.
std::string summary_line(const std::string& nest, const nlohmann::json& r, const std::string& program) {
  std::string line = nest + ": " + std::to_string(r["pierces"].get<std::size_t>()) + " pierces, cut " +
                     format_fixed(r["cut_length_mm"].get<double>(), 1) + " mm, rapid " +
                     format_fixed(r["rapid_length_mm"].get<double>(), 1) + " mm, " +
                     std::to_string(r["frames"].get<std::size_t>()) + " frames, T_cut " +
                     format_fixed(r["t_cut_s"].get<double>(), 2) + " s (" +
                     format_fixed(r["t_cut_const_speed_s"].get<double>(), 2) + " s at the set speed), technique " +
                     r["chosen"].get<std::string>();
  // How far from the best route this one can be at most, as the HTML page says it.
  if (const std::string q = io::route_quality(r); !q.empty()) line += ", route " + q;
  return line + " -> " + program;
}

// Reads, optimizes and writes one nest.
NestOutcome cut_nest(const std::string& nest, const Outputs& out, const pipeline::OptimizeOptions& po,
                     const io::NestLoadOptions& load_options, ProgressLine& progress) {
  // After Ctrl-C the nests already under way still write their best program; the rest do not start.
  if (StopToken::global().cancelled()) return {kInputError, nest + ": not started (interrupted)", {}, {}, true};
  auto loaded = io::load_nest(nest, load_options);
  if (!loaded) return {kInputError, format(loaded.error()), {}, {}};
  pipeline::OptimizeOptions mine = po;
  mine.title = "cutroute " + std::filesystem::path(nest).filename().string();
  auto res = pipeline::optimize_nest(*loaded, mine, StopToken::global(), progress.for_job(nest));
  if (!res) {
    Diagnostic d = res.error();
    if (d.file.empty()) d.file = nest;
    return {kInputError, format(d), {}, {}};
  }
  // All outputs or none: a report or picture that fails to write leaves no program behind, and
  // a program that fails leaves no report of it.
  io::RoutePictureOptions pic;
  pic.title = std::filesystem::path(nest).filename().string();
  pic.caption = io::report_caption(res->report);
  pic.compensation_at_risk = io::compensation_at_risk(res->report);
  for (const auto& o : loaded->open_paths)
    pic.not_cut.emplace_back(o.path, "not cut: open contour" + (o.line ? " (line " + std::to_string(*o.line) + ", layer " + o.layer + ")"
                                                                      : std::string(" (layer ") + o.layer + ")"));
  pic.gaps_closed = loaded->gaps_closed;
  std::vector<io::OutputFile> files;
  if (!out.report.empty()) files.push_back({out.report, json_text(res->report) + "\n"});
  if (!out.svg.empty()) files.push_back({out.svg, io::route_to_svg(loaded->nest, res->toolpath, pic)});
  if (!out.html.empty())
    files.push_back({out.html, io::route_to_html(loaded->nest, res->toolpath, io::report_summary(res->report), pic)});
  files.push_back({out.program, res->program.text});
  if (const Status st = io::write_files_atomic(files); !st) return {kInputError, format(st.error()), {}, {}};
  return {kOk, summary_line(nest, res->report, out.program), printed_warnings(nest, res->diagnostics, *loaded, res->report),
          res->report};
}

// A batch's sheets in one table with their totals, for a quote or a shift plan.
int write_batch_summary(const Opts& o, const std::vector<Outputs>& outs, const std::vector<NestOutcome>& done) {
  std::vector<io::BatchEntry> entries(o.nests.size());
  double t_cut = 0;
  std::size_t cut = 0;
  for (std::size_t i = 0; i < o.nests.size(); ++i) {
    const bool ok = done[i].code == kOk;
    entries[i] = {o.nests[i], ok ? outs[i].program : std::string(), ok ? done[i].report : nlohmann::json(),
                  ok ? std::string() : done[i].message, done[i].not_started};
    if (ok) t_cut += done[i].report["t_cut_s"].get<double>(), ++cut;
  }
  const auto summary = (std::filesystem::path(o.out) / "summary.csv").string();
  if (const Status st = io::write_file_atomic(summary, io::batch_summary_csv(entries)); !st) {
    std::cerr << "cutroute: " << format(st.error()) << '\n';
    return kInputError;
  }
  if (!o.quiet)
    std::cout << cut << " of " << o.nests.size() << " nests cut, T_cut " << format_fixed(t_cut, 2) << " s in all -> " << summary << '\n';
  return kOk;
}

int run(const Opts& o) {
  auto load_options = to_load_options(o.input);
  auto po = load_options ? optimize_options(o) : Result<pipeline::OptimizeOptions>(load_options.error());
  auto outs = po ? output_paths(o) : Result<std::vector<Outputs>>(po.error());
  if (!outs) {
    std::cerr << "cutroute: " << outs.error().message << '\n';
    return kUsageError;
  }
  // A batch's folder that cannot be made: its own reason (permission denied), not the missing
  // file's that each output would report.
  if (o.nests.size() > 1) {
    std::error_code ec;
    if (!std::filesystem::is_directory(o.out, ec) && !std::filesystem::create_directories(o.out, ec) && ec) {
      std::cerr << "cutroute: " << o.out << ": error: cannot make the output folder: " << ec.message() << '\n';
      return kInputError;
    }
  }
  // Where the outputs cannot go is said before the solving, not after it (10 s at the default limit).
  for (const Outputs& out : *outs)
    for (const std::string* path : {&out.program, &out.report, &out.svg, &out.html})
      if (!path->empty())
        if (Status st = io::check_output(*path); !st) {
          std::string msg = format(st.error());
          // The hint is about -o: a --report, --svg or --html naming a folder is told only that
          // (the hint sent users to an -o they never gave).
          if (o.nests.size() == 1 && path == &out.program && msg.find("is a folder") != std::string::npos)
            msg += " (with one nest, -o names the program file; several nests write into -o DIR)";
          std::cerr << "cutroute: " << msg << '\n';
          return kInputError;
        }
  const std::size_t workers = std::min<std::size_t>(o.nests.size(), std::max(1u, std::thread::hardware_concurrency()));
  po->threads = o.threads > 0 ? std::max(1, o.threads / static_cast<int>(workers))
                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / static_cast<int>(workers));
  ProgressLine progress(show_progress(o.quiet));
  std::vector<NestOutcome> done(o.nests.size());
  std::atomic<std::size_t> next{0};
  // An exception (out of memory, a bug) fails its nest, not the batch: thrown in a worker thread
  // it would end the process without a word.
  auto work = [&] {
    for (std::size_t i = next++; i < o.nests.size(); i = next++) {
      try {
        done[i] = cut_nest(o.nests[i], (*outs)[i], *po, *load_options, progress);
      } catch (const std::bad_alloc&) {
        done[i] = {kInputError, o.nests[i] + ": error: out of memory", {}, {}};
      } catch (const std::exception& e) {
        done[i] = {kInputError, o.nests[i] + ": error: internal error: " + e.what(), {}, {}};
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  progress.done();

  int code = kOk;
  bool stopped = false;  // sheets left undone by Ctrl-C or SIGTERM: the batch is incomplete
  for (std::size_t i = 0; i < o.nests.size(); ++i) {
    std::cerr << done[i].warnings;
    if (done[i].code != kOk) {
      std::cerr << "cutroute: " << done[i].message << '\n';
      code = done[i].code;
      stopped = stopped || done[i].not_started;
      // A batch's outputs for a sheet that failed: a file of that name from an earlier run into the
      // folder would pass for this sheet's program (another drawing's, or an older one).
      if (o.nests.size() > 1) {
        const Outputs& f = (*outs)[i];
        for (const std::string* path : {&f.program, &f.report, &f.svg, &f.html}) {
          std::error_code ec;
          if (std::filesystem::is_regular_file(*path, ec) && std::filesystem::remove(*path, ec))
            std::cerr << "cutroute: " << *path << ": removed, from an earlier run: no output stands for a sheet that failed\n";
        }
      }
    } else if (!o.quiet) {
      // With an output on stdout (-o -), the summary goes to stderr, out of the program's stream.
      const Outputs& f = (*outs)[i];
      const bool piped = f.program == "-" || f.report == "-" || f.svg == "-" || f.html == "-";
      (piped ? std::cerr : std::cout) << done[i].message << '\n';
    }
  }
  if (o.nests.size() > 1)
    if (const int st = write_batch_summary(o, *outs, done); st != kOk) return st;
  // Not an input error (2): a script that reruns the batch must tell "stopped" from "bad sheet".
  if (stopped) return kSignalBase + (interrupt_signal() != 0 ? interrupt_signal() : SIGINT);
  return code;
}

// Options given that the rest of the command line leaves without effect (a tab width without
// --tabs, a chain gap for the standard technique): said, since the user expected them to act.
std::vector<std::string> idle_options(const CLI::App& app, const Opts& o) {
  std::vector<std::string> out;
  auto given = [&](const char* name) { return app.count(name) > 0; };
  auto idle = [&](std::initializer_list<const char*> names, bool acts, const std::string& why) {
    for (const char* n : names)
      if (given(n) && !acts) out.push_back(std::string(n) + " has no effect " + why);
  };
  idle({"--chain-gap"}, o.technique == "chain" || o.technique == "auto", "with --technique " + o.technique);
  idle({"--multi-min-span", "--multi-pieces"}, o.technique == "multi" || o.multi_segment, "without --technique multi or --multi-segment");
  idle({"--tab-width", "--tab-lead-in"}, o.rules.tabs > 0, "without --tabs");
  idle({"--heat-weight", "--heat-memory"}, o.rules.heat_distance_mm > 0, "without --heat-distance");
  idle({"--tip-up-weight", "--tip-up-margin"}, o.rules.avoid_tip_up, "without --avoid-tip-up");
  idle({"--avoid-tip-up"}, o.rules.tabs <= 0, "with --tabs: parts held by tabs do not tip");
  idle({"--sheet-weight", "--sheet-band"}, !o.sheet_clamp.empty(), "without --sheet-clamp");
  idle({"--allow-kerf-overlap"}, o.kerf_mode == "cam", "without --kerf-mode cam");
  idle({"--keep-compensation"}, o.kerf_mode == "controller", "without --kerf-mode controller");
  idle({"--kerf"}, o.kerf_mode != "none", "with --kerf-mode none");
  return out;
}

// Shop rules (docs/SHOP-RULES.md): every rule off unless asked for.
void add_shop_rule_options(CLI::App* app, pipeline::ShopRules& r, std::string& clamp, std::string& tab_lead_in) {
  const char* g = "Shop rules";
  app->add_option("--heat-distance", r.heat_distance_mm, "Heat: consecutive cuts at least this far apart where possible [mm] (0: off)")
      ->check(finite_range(0.0, 1e5))->group(g);
  app->add_option("--heat-weight", r.heat_weight, "Heat: price of a too-close pair [s]")->check(finite_range(0.0, 1e6))->capture_default_str()->group(g);
  app->add_option("--heat-memory", r.heat_memory, "Heat: segments looked back (each further one counts half)")
      ->check(CLI::Range(1, 16))->capture_default_str()->group(g);
  app->add_flag("--avoid-tip-up", r.avoid_tip_up, "Tip-up: rapids go around parts already cut free")->group(g);
  app->add_option("--tip-up-weight", r.tip_up_weight, "Tip-up: price of a rapid over a freed part while sequencing [s]")
      ->check(finite_range(0.0, 1e6))->capture_default_str()->group(g);
  app->add_option("--tip-up-margin", r.tip_up_margin_mm, "Tip-up: detour distance from freed parts [mm]")
      ->check(finite_range(0.0, 1e3))->capture_default_str()->group(g);
  app->add_flag("--part-rigidity", r.part_rigidity,
                "Part rigidity: outer contours entered at the corner toward the uncut material (standard technique only)")->group(g);
  app->add_option("--sheet-clamp", clamp, "Sheet rigidity: clamped side; the order sweeps away from it")
      ->check(CLI::IsMember({"left", "right", "bottom", "top"}))->group(g);
  app->add_option("--sheet-weight", r.sheet_weight_per_mm, "Sheet rigidity: price per mm behind the sweep front [s/mm]")
      ->check(finite_range(0.0, 1e6))->capture_default_str()->group(g);
  app->add_option("--sheet-band", r.sheet_band_mm, "Sheet rigidity: allowed step back behind the front [mm]")
      ->check(finite_range(0.0, 1e6))->capture_default_str()->group(g);
  app->add_option("--tabs", r.tabs, "Micro-joints: uncut tabs per outer contour (0: off)")
      ->check(CLI::Range(0, 64))->group(g);
  app->add_option("--tab-width", r.tab_width_mm, "Micro-joints: tab width [mm]")
      ->check(finite_range(0.001, 1e3))->capture_default_str()->group(g);
  app->add_option("--tab-lead-in", tab_lead_in,
                  "Micro-joints: each cut after a tab starts with a lead-in from scrap (on), on the path (off), or "
                  "auto: with a lead-in where the dialect cannot keep compensation on over the tab (plasma)")
      ->check(CLI::IsMember({"auto", "on", "off"}))->capture_default_str()->group(g);
}

}  // namespace

void add_optimize(CLI::App& root, Commands& out) {
  auto o = std::make_shared<Opts>();
  auto* app = root.add_subcommand("optimize", "Optimize the cutting route of DXF nest(s) and write the G-code program");
  app->add_option("NEST", o->nests, "DXF nest file(s); several are optimized in parallel")->required();
  app->add_option("-o,--output", o->out, "Program file (one nest; default: the nest's name with .ngc, in the current folder) or output folder (several nests)");
  app->add_option("--report", o->report, "Write the JSON report to this file");
  app->add_option("--svg", o->svg, "Write the route picture to this SVG file");
  app->add_option("--html", o->html, "Write a self-contained HTML page with the animated route");
  app->add_option("--material", o->material, "Material (Table 1 name or alias), default from the machine profile")
      ->check(CLI::Validator([](std::string& v) { return v.empty() ? std::string("empty material name") : std::string(); }, "NAME"));
  app->add_option("--thickness", o->thickness, "Sheet thickness [mm]")->check(finite_range(1e-3, 1000));
  app->add_option("--machine", o->machine, "Machine profile JSON (default: the built-in ByStar 3015-class laser)");
  app->add_flag("--interpolate", o->interpolate, "Interpolate speeds between Table 1 thicknesses");
  app->add_option("--objective", o->objective, "time (eq. 10) or cost (eq. 3)")->check(CLI::IsMember({"time", "cost"}));
  app->add_option("--time-limit", o->time_limit, "Time budget of the optimisation [s]: cut jobs, solver, refinement, technique and lead comparison (reading and writing come on top); 0 = stop on stagnation only")->check(finite_range(0.0, 86400.0))->capture_default_str();
  app->add_option("--work-limit", o->work_limit_m,
                  "Work budget of each route search [millions of units] (0: automatic); unlike time it does not depend on the "
                  "machine: with --time-limit 0 a run is bounded and reproducible (report: solver.work_m)")
      ->check(finite_range(0.0, 1e9));
  app->add_option("--seed", o->seed, "Random seed: same seed, input and options give identical outputs")->capture_default_str();
  app->add_option("--threads", o->threads, "Threads of the route solver and of the cut jobs: entry candidates, chains (0: all cores; several nests share them)")->check(CLI::Range(0, 64));
  app->add_option("--solver", o->solver, "auto, exact or heuristic")->check(CLI::IsMember({"auto", "exact", "heuristic"}));
  app->add_option("--start", o->start, "Machine start and park position X,Y [mm] (default 0,0)");
  app->add_option("--kerf", o->kerf, "Kerf width [mm] (default from the machine profile)")->check(finite_range(0.0, 20.0));
  app->add_option("--kerf-mode", o->kerf_mode,
                  "controller: G41/G42, the machine offsets the drawn contours; cam: the program offsets the "
                  "toolpath by kerf/2 to the scrap side (arcs stay G2/G3, no G41/G42); none: the drawn contours")
      ->check(CLI::IsMember({"controller", "cam", "none"}));
  app->add_flag("--keep-compensation", o->keep_compensation,
                "With --kerf-mode controller: keep G41/G42 on cuts whose drawing has details finer than the kerf, which the "
                "controller refuses (LinuxCNC stops there); by default they are written on their kerf offset without it");
  app->add_option("--dialect", o->dialect,
                  "Post-processor: generic, plasma-thc, or a dialect JSON file (default: the machine profile's dialect; "
                  "generic for the built-in profile)");
  app->add_option("--entry-step", o->entry_step, "Spacing of entry candidates along edges [mm] (0: adaptive)")
      ->check(finite_range(0.0, 1e6));
  app->add_flag("--allow-crossing", o->allow_crossing,
                "Cut a drawing whose contours cross each other (each contour once, with warnings)");
  app->add_flag("--allow-kerf-overlap", o->allow_kerf_overlap,
                "With --kerf-mode cam, cut contours closer than the kerf anyway (one cuts into the other; warnings)");
  app->add_option("--technique", o->technique,
                  "Basic segments: standard (one per contour), chain (neighbouring parts joined by bridges), "
                  "common (shared edges cut once), multi (long contours cut in pieces, ECP), auto (each available "
                  "one solved, the fastest kept, with shop rules the fastest plus the rules' price; multi only with "
                  "--multi-segment; only standard with --part-rigidity)")
      ->check(CLI::IsMember({"standard", "chain", "common", "multi", "auto"}))
      ->capture_default_str();
  app->add_option("--chain-gap", o->chain_gap, "Chain cutting: largest gap between parts bridged [mm]")
      ->check(finite_range(0.0, 1000.0))
      ->capture_default_str();
  app->add_flag("--multi-segment", o->multi_segment,
                "Multi-segment cutting (ECP): --technique auto also compares long contours cut in pieces");
  app->add_option("--multi-min-span", o->multi.min_span_mm,
                  "Multi-segment cutting: split a contour only where its split points lie this far apart [mm]")
      ->check(finite_range(0.0, 1e6))
      ->capture_default_str();
  app->add_option("--multi-pieces", o->multi.max_pieces, "Multi-segment cutting: pieces per split contour")
      ->check(CLI::Range(2, 8))
      ->capture_default_str();
  app->add_flag("-q,--quiet", o->quiet, "No progress and no summary");
  add_shop_rule_options(app, o->rules, o->sheet_clamp, o->tab_lead_in);
  add_input_options(app, o->input);
  out.push_back({app, [o, app] {
                   for (const auto& w : idle_options(*app, *o)) std::cerr << "cutroute: warning: " << w << '\n';
                   return run(*o);
                 },
                 true});
}

}  // namespace cutroute::cli
