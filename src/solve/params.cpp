#include <cutroute/solve/params.hpp>

#include <string>

namespace cutroute::solve {

const char* to_string(SolverKind k) {
  switch (k) {
    case SolverKind::automatic: return "auto";
    case SolverKind::exact: return "exact";
    case SolverKind::heuristic: return "heuristic";
  }
  return "?";
}

SolveParams SolveParams::standard() { return SolveParams{}; }

SolveParams SolveParams::fast() {
  SolveParams p;
  p.stagnation_rounds = 2;
  p.min_stagnation_work = 10000;
  p.exact_auto_max_work = 5.0e7;
  return p;
}

SolveParams SolveParams::thorough() {
  SolveParams p;
  p.stagnation_rounds = 60;
  p.min_stagnation_work = 10000000;
  p.work_budget = -1.0;
  p.time_limit_s = 600.0;
  p.exact_auto_max_work = 4.0e9;
  return p;
}

std::vector<std::string> check(const SolveParams& p) {
  std::vector<std::string> out;
  auto num = [](double v) { return std::to_string(v); };
  if (p.threads < 0) out.push_back("threads must be >= 0 (got " + std::to_string(p.threads) + ")");
  if (p.threads > 256) out.push_back("threads must be <= 256 (got " + std::to_string(p.threads) + ")");
  if (!(p.time_limit_s == p.time_limit_s)) out.push_back("time_limit_s is not a number");
  if (p.round_iterations < 0) out.push_back("round_iterations must be >= 0 (got " + std::to_string(p.round_iterations) + ")");
  if (p.stagnation_rounds < 0) out.push_back("stagnation_rounds must be >= 0 (got " + std::to_string(p.stagnation_rounds) + ")");
  if (!(p.max_removal_fraction >= 0.0 && p.max_removal_fraction <= 1.0))
    out.push_back("max_removal_fraction must be in [0, 1] (got " + num(p.max_removal_fraction) + ")");
  if (!(p.accept_threshold >= 0.0 && p.accept_threshold <= 10.0))
    out.push_back("accept_threshold must be in [0, 10] (got " + num(p.accept_threshold) + ")");
  if (p.exact_memory_limit_bytes < (std::size_t{1} << 20)) out.push_back("exact_memory_limit_bytes must be >= 1 MiB");
  if (!(p.exact_auto_max_work >= 0.0)) out.push_back("exact_auto_max_work must be >= 0");
  if (p.epoch_rounds > 1000000) out.push_back("epoch_rounds must be <= 1000000 (got " + std::to_string(p.epoch_rounds) + ")");
  if (!(p.work_budget == p.work_budget)) out.push_back("work_budget is not a number");
  if (p.population_size > 10000) out.push_back("population_size must be <= 10000 (got " + std::to_string(p.population_size) + ")");
  if (p.min_stagnation_work < 0) out.push_back("min_stagnation_work must be >= 0");
  if (p.target_cost && *p.target_cost < 0) out.push_back("target_cost must be >= 0");
  return out;
}

}  // namespace cutroute::solve
