// cutroute gtsp: solve a GTSP / SOP / PCGLNS instance file and print objective, status and time.
#include <charconv>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/stop.hpp>
#include <cutroute/io/instance.hpp>
#include <cutroute/solve/solve.hpp>

#include "commands.hpp"
#include "input_options.hpp"
#include "progress_line.hpp"

namespace cutroute::cli {

namespace {

struct GtspOptions {
  std::string instance;
  double time_limit_s = 60.0;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string solver = "auto";
  bool json = false;
  bool quiet = false;
  double work_limit_m = 0.0;
};

std::string seconds_text(double s) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, s, std::chars_format::fixed, 3);
  return std::string(buf, r.ptr);
}

int run_gtsp(const GtspOptions& o) {
  auto inst = io::read_instance(o.instance);
  if (!inst) return fail(inst.error());
  solve::SolveParams params;
  params.time_limit_s = o.time_limit_s;
  params.seed = o.seed;
  params.threads = o.threads;
  params.work_budget = o.work_limit_m * 1e6;
  params.solver = o.solver == "exact" ? solve::SolverKind::exact
                  : o.solver == "heuristic" ? solve::SolverKind::heuristic
                                            : solve::SolverKind::automatic;
  if (const auto problems = solve::check(params); !problems.empty()) {
    std::cerr << "cutroute: error: " << problems.front() << '\n';
    return kUsageError;
  }
  // Runs take a minute by default: on a terminal the best cost so far is shown as it improves.
  ProgressLine progress(show_progress(o.quiet), 0);
  const solve::Solution s = solve::solve(inst->problem, params, StopToken::global(), progress.for_job(inst->name));
  progress.done();
  if (o.json) {
    nlohmann::json j;
    j["instance"] = inst->name;
    j["status"] = solve::to_string(s.status);
    j["time_s"] = s.stats.seconds;
    j["solver"] = s.stats.solver;
    j["threads"] = s.stats.threads;
    j["iterations"] = s.stats.iterations;
    j["work_m"] = s.stats.work / 1e6;
    if (!s.route.empty()) j["objective"] = s.cost;
    else j["objective"] = nullptr;
    auto tour = nlohmann::json::array();
    for (auto v : s.route) tour.push_back(v.value() + 1);
    j["tour"] = tour;
    if (s.lower_bound) j["lower_bound"] = *s.lower_bound;
    if (interrupt_signal() != 0) j["interrupted"] = true;
    std::cout << json_text(j, -1) << '\n';
  } else {
    std::cout << "instance:  " << inst->name << '\n';
    if (!s.route.empty()) std::cout << "objective: " << s.cost << '\n';
    std::cout << "status:    " << solve::to_string(s.status) << '\n';
    if (s.lower_bound) {
      std::cout << "lower bound: " << *s.lower_bound;
      // The share of the objective the bound leaves open: how much better any route could be.
      if (!s.route.empty() && s.cost > 0 && *s.lower_bound < s.cost)
        std::cout << " (gap " << format_fixed(100.0 * static_cast<double>(s.cost - *s.lower_bound) / static_cast<double>(s.cost), 2)
                  << " % of the objective)";
      std::cout << '\n';
    }
    std::cout << "time:      " << seconds_text(s.stats.seconds) << " s (" << s.stats.solver << ", " << s.stats.threads
              << (s.stats.threads == 1 ? " thread" : " threads") << ")\n";
  }
  // Stopped early, the route is the best found by then, with the status a time limit gives it: a
  // benchmark table must not take it for a full run's.
  if (interrupt_signal() != 0)
    std::cerr << "cutroute: " << o.instance << ": warning: the run was interrupted (Ctrl-C, SIGTERM or a closed terminal): the route is the best "
              << "found before the stop\n";
  if (s.status == solve::SolveStatus::infeasible) {
    std::cerr << "cutroute: " << o.instance << ": error: the instance has no feasible route\n";
    return kInputError;
  }
  if (s.status == solve::SolveStatus::no_solution) {
    std::cerr << "cutroute: " << o.instance << ": error: no route without forbidden arcs found (time limit, or infeasible)\n";
    return kInputError;
  }
  return kOk;
}

}  // namespace

void add_gtsp(CLI::App& root, Commands& out) {
  auto opts = std::make_shared<GtspOptions>();
  auto* app = root.add_subcommand("gtsp", "Solve a routing instance (.gtsp GTSPLIB, .sop TSPLIB SOP, .pcglns PCGTSP)");
  app->add_option("instance", opts->instance, "Instance file")->required();
  app->add_option("--time-limit", opts->time_limit_s, "Wall-clock limit in seconds (default 60)")->check(CLI::NonNegativeNumber);
  app->add_option("--seed", opts->seed, "Random seed (default 1)");
  app->add_option("--threads", opts->threads, "Search threads (default: all cores)")->check(CLI::Range(0, 256));
  app->add_option("--solver", opts->solver, "auto | exact | heuristic")->check(CLI::IsMember({"auto", "exact", "heuristic"}));
  app->add_option("--work-limit", opts->work_limit_m,
                  "Work budget of the heuristic [millions of units] (0: automatic); machine-independent, unlike the time limit")
      ->check(finite_range(0.0, 1e9));
  app->add_flag("--json", opts->json, "Print one JSON object");
  app->add_flag("-q,--quiet", opts->quiet, "No progress line on the terminal");
  out.push_back({app, [opts] { return run_gtsp(*opts); }, true});
}

}  // namespace cutroute::cli
