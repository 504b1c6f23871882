// cutroute machining: read a boring problem (JSON), optimise vc and f, print the report, write SVG/CSV.
#include <iostream>
#include <string>

#include <cutroute/io/output_file.hpp>
#include <cutroute/machining/optimize.hpp>
#include <cutroute/machining/problem_json.hpp>
#include <cutroute/machining/report.hpp>

#include "commands.hpp"

namespace cutroute::cli {

namespace {

struct MachiningOptions {
  std::string problem;
  bool json = false;
  std::string svg;
  std::string csv;
  std::string method = "grid";
  bool fig5 = true;
};

int run_machining(const MachiningOptions& o) {
  auto text = io::read_file(o.problem);
  if (!text) return fail(text.error());
  auto problem = machining::read_problem_json(*text, o.problem);
  if (!problem) return fail(problem.error());
  const machining::Problem& p = *problem;

  machining::OptimizeParams params;
  params.method = o.method == "nlopt" ? machining::Method::nlopt_cobyla : machining::Method::grid_golden;
  const machining::OptimizeResult result = machining::optimize(p, params);
  machining::RunOutput out;
  out.problem = &p;
  out.result = &result;
  if (o.fig5 && p.accuracy) out.fig5 = machining::optimize_fig5(p, p.search.grid_vc, p.search.grid_f);
  if (!p.K_TZ_sweep.empty()) out.sweep = machining::cost_of_accuracy(p, p.K_TZ_sweep, params);

  if (!o.svg.empty()) {
    if (auto st = io::write_file_atomic(o.svg, machining::report_svg(out)); !st) return fail(st.error());
  }
  if (!o.csv.empty()) {
    if (auto st = io::write_file_atomic(o.csv, machining::report_csv(out)); !st) return fail(st.error());
  }
  if (o.json) {
    std::cout << machining::report_json(out).dump(2) << '\n';
  } else {
    std::cout << machining::report_text(out);
  }
  // An infeasible problem is an answer, not an input error: exit 0 with status "infeasible".
  return kOk;
}

}  // namespace

void add_machining(CLI::App& root, Commands& out) {
  auto opts = std::make_shared<MachiningOptions>();
  auto* app = root.add_subcommand("machining", "optimise cutting speed and feed of a boring transition (MACHINING.md)");
  app->add_option("problem", opts->problem, "problem file (JSON, see docs/MACHINING-SCHEMA.md)")->required();
  app->add_flag("--json", opts->json, "print the full report as JSON");
  app->add_option("--svg", opts->svg, "write the cost map (feasible region, valley, near-optimal contours) as SVG");
  app->add_option("--csv", opts->csv, "write the valley and the grid as CSV");
  app->add_option("--method", opts->method, "grid (grid + golden section, the reference) or nlopt (COBYLA)")
      ->check(CLI::IsMember({"grid", "nlopt"}));
  app->add_flag("!--no-fig5", opts->fig5, "skip the Fig. 5 two-stage cross-check");
  out.push_back({app, [opts] { return run_machining(*opts); }});
}

}  // namespace cutroute::cli
