#include "machining/nlopt_backend.hpp"

#include <cmath>

#include <cutroute/core/tolerances.hpp>

#ifdef CUTROUTE_WITH_NLOPT
#include <nlopt.hpp>
#endif

namespace cutroute::machining {

bool nlopt_available() {
#ifdef CUTROUTE_WITH_NLOPT
  return true;
#else
  return false;
#endif
}

namespace detail {

#ifdef CUTROUTE_WITH_NLOPT
namespace {

struct Ctx {
  const Problem* p;
  int set;
  long* evals;
};
struct ConstraintCtx {
  Ctx* ctx;
  int k;
};

double objective(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  auto* c = static_cast<Ctx*>(data);
  ++*c->evals;
  return evaluate(*c->p, std::exp(x[0]), std::exp(x[1]), c->set).cost.total;
}
double constraint(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  auto* cc = static_cast<ConstraintCtx*>(data);
  return evaluate(*cc->ctx->p, std::exp(x[0]), std::exp(x[1]), cc->ctx->set).g[cc->k].g;
}

}  // namespace

PointEval cobyla_refine(const Problem& p, int set, const SearchBox& box, const PointEval& start,
                        long& evals) {
  Ctx ctx{&p, set, &evals};
  nlopt::opt opt(nlopt::LN_COBYLA, 2);
  opt.set_lower_bounds({std::log(box.vc[0]), std::log(box.f[0])});
  opt.set_upper_bounds({std::log(box.vc[1]), std::log(box.f[1])});
  opt.set_min_objective(objective, &ctx);
  std::vector<ConstraintCtx> cons;
  cons.reserve(kConstraintCount);
  for (int k = 0; k < kConstraintCount; ++k) {
    if (start.g[k].enabled) cons.push_back({&ctx, k});
  }
  for (auto& c : cons) opt.add_inequality_constraint(constraint, &c, 0.0);
  opt.set_xtol_rel(1e-12);
  opt.set_maxeval(20000);
  std::vector<double> x{std::log(start.vc), std::log(start.f)};
  double val = 0.0;
  try {
    opt.optimize(x, val);
  } catch (const nlopt::roundoff_limited&) {
    // x holds the last point; it is judged below like a converged one.
  } catch (const std::exception&) {
    return start;  // failed runs keep the grid optimum
  }
  const PointEval e = evaluate(p, std::exp(x[0]), std::exp(x[1]), set);
  if (e.feasible() && e.cost.total <= start.cost.total) return e;
  return start;
}
#else
PointEval cobyla_refine(const Problem&, int, const SearchBox&, const PointEval& start, long&) {
  return start;
}
#endif

}  // namespace detail
}  // namespace cutroute::machining
