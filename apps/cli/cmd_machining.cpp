// cutroute machining: read a boring problem (JSON), optimise vc and f, print the report, write SVG/CSV.
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <cutroute/core/file.hpp>
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

// "out.svg" -> "out.t2.svg" for transition 2 of a multi-transition file.
std::string numbered(const std::string& path, std::size_t k) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  const std::string tag = ".t" + std::to_string(k + 1);
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path + tag;
  return path.substr(0, dot) + tag + path.substr(dot);
}

int run_machining(const MachiningOptions& o) {
  // Both into one file would leave only the CSV, silently.
  if (!o.svg.empty() && !o.csv.empty() && io::same_output(o.svg, o.csv)) {
    std::cerr << "cutroute: --svg and --csv name the same output: " << o.csv << '\n';
    return kUsageError;
  }
  auto text = read_file(o.problem);
  if (!text) return fail(text.error());
  auto parts = machining::read_transitions_json(*text, o.problem);
  if (!parts) return fail(parts.error());

  machining::OptimizeParams params;
  params.method = o.method == "nlopt" ? machining::Method::nlopt_cobyla : machining::Method::grid_golden;
  const std::size_t count = parts->items.size();
  std::vector<machining::OptimizeResult> results(count);
  nlohmann::json reports = nlohmann::json::array();
  std::string text_out;
  double total = 0.0;
  std::string status = "optimal";
  // Every transition's pictures and tables are written together once all are made: one by one, a
  // failure (or a stop) at a later transition left the earlier ones' files behind.
  std::vector<io::OutputFile> files;
  for (std::size_t k = 0; k < count; ++k) {
    const machining::Problem& p = parts->items[k];
    results[k] = machining::optimize(p, params);
    machining::RunOutput out;
    out.problem = &p;
    out.result = &results[k];
    if (o.fig5 && p.accuracy) out.fig5 = machining::optimize_fig5(p, p.search.grid_vc, p.search.grid_f);
    if (!p.K_TZ_sweep.empty()) out.sweep = machining::cost_of_accuracy(p, p.K_TZ_sweep, params);
    const std::string svg = parts->is_list ? numbered(o.svg, k) : o.svg;
    const std::string csv = parts->is_list ? numbered(o.csv, k) : o.csv;
    if (!o.svg.empty()) files.push_back({svg, machining::report_svg(out)});
    if (!o.csv.empty()) files.push_back({csv, machining::report_csv(out)});
    reports.push_back(machining::report_json(out));
    if (parts->is_list) text_out += "--- transition " + std::to_string(k + 1) + "\n";
    text_out += machining::report_text(out);
    if (results[k].solution) total += results[k].solution->cost.total;
    if (results[k].status == machining::Status::infeasible)
      status = "infeasible";
    else if (results[k].status == machining::Status::warning && status == "optimal")
      status = "warning";
  }
  if (auto st = io::write_files_atomic(files); !st) return fail(st.error());
  if (o.json) {
    if (!parts->is_list) {
      std::cout << json_text(reports[0]) << '\n';
    } else {
      // CT of the part is the sum over its transitions (each carries its own fixed share).
      nlohmann::json j;
      j["name"] = parts->name;
      j["status"] = status;
      j["total_cost_cu"] = status == "infeasible" ? nlohmann::json(nullptr) : nlohmann::json(total);
      j["transitions"] = reports;
      std::cout << json_text(j) << '\n';
    }
  } else {
    std::cout << text_out;
    if (parts->is_list) {
      std::cout << "--- part: status " << status
                << ", total CT = " << (status == "infeasible" ? std::string("n/a") : std::to_string(total))
                << " CU\n";
    }
  }
  // An infeasible problem is an answer, not an input error: exit 0 with status "infeasible".
  return kOk;
}

}  // namespace

void add_machining(CLI::App& root, Commands& out) {
  auto opts = std::make_shared<MachiningOptions>();
  auto* app = root.add_subcommand("machining",
                                  "Optimise cutting speed and feed of boring on a machining centre by minimum cost (docs/MACHINING-SCHEMA.md)");
  app->add_option("problem", opts->problem, "problem file (JSON, see docs/MACHINING-SCHEMA.md)")->required();
  app->add_flag("--json", opts->json, "print the full report as JSON");
  app->add_option("--svg", opts->svg,
                  "write the cost map (feasible region, valley, near-optimal contours) as SVG");
  app->add_option("--csv", opts->csv, "write the valley and the grid as CSV");
  app->add_option("--method", opts->method, "grid (grid + golden section, the reference) or nlopt (COBYLA)")
      ->check(CLI::IsMember({"grid", "nlopt"}));
  app->add_flag("!--no-fig5", opts->fig5, "skip the Fig. 5 two-stage cross-check");
  out.push_back({app, [opts] { return run_machining(*opts); }});
}

}  // namespace cutroute::cli
