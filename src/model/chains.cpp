#include <cutroute/model/chains.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include <cutroute/core/parallel.hpp>
#include <cutroute/geometry/intersect.hpp>
#include <cutroute/geometry/segment_set.hpp>
#include <cutroute/geometry/spatial_index.hpp>

namespace cutroute::model {

using geometry::Contour;
using geometry::Vec2;

namespace {

struct Sample {
  double s = 0;   // arc length along the stored contour [mm]
  Vec2 p;
};

// Points along c every `step` mm and at every vertex, only those inside `window`.
std::vector<Sample> samples(const Contour& c, double step, const geometry::Box& window) {
  std::vector<Sample> out;
  const std::size_t n = geometry::segment_count(c);
  double acc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto seg = geometry::segment(c, i);
    const double len = seg.length();
    const int parts = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int k = 0; k < parts; ++k) {
      const double t = static_cast<double>(k) / parts;
      const Vec2 p = seg.point_at(t);
      if (window.contains(p)) out.push_back({acc + t * len, p});
    }
    acc += len;
  }
  return out;
}

// Sampling step along a contour: fine enough to find a corner-to-edge gap to a fraction of a mm,
// coarse enough that a long outline costs at most a few thousand distance queries.
double sample_step(const Contour& c) { return std::clamp(geometry::length(c) / 2000.0, 0.5, 5.0); }

// Smallest distance from the samples of a (near b) to b, and where on a; only distances up to
// max_gap are measured (farther: infinity). b's segments indexed: up to 2000 samples against an
// outline of hundreds of segments each.
struct Nearest {
  double gap = std::numeric_limits<double>::infinity();
  double s = 0;
};
Nearest nearest(const Contour& a, const geometry::SegmentSet& b, double max_gap) {
  Nearest best;
  for (const auto& q : samples(a, sample_step(a), b.box.inflated(max_gap))) {
    b.index.visit(geometry::Box{q.p.x, q.p.y, q.p.x, q.p.y}.inflated(max_gap), [&](std::uint32_t k) {
      const double d = geometry::closest_point(b.segments[k], q.p).distance;
      if (d < best.gap) best = {d, q.s};
      return true;
    });
  }
  return best;
}

// Union-find over job contour indices, with run sizes.
struct Runs {
  std::vector<std::size_t> parent, size;
  explicit Runs(std::size_t n) : parent(n), size(n, 1) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    parent[b] = a;
    size[a] += size[b];
  }
};

class ChainBuilder {
 public:
  ChainBuilder(const Nest& nest, const EntryPlanner& planner, const CutJob& base, const std::vector<std::int32_t>& seg_of,
               const EntryOptions& entries, const ChainOptions& options)
      : nest_(nest), planner_(planner), base_(base), seg_of_(seg_of), entries_(entries), opt_(options) {}

  // All admissible candidates of the run in both orders, best first, at most max_candidates.
  std::vector<EntryCandidate> candidates(const std::vector<ContourId>& run) const {
    std::vector<ContourId> back(run.rbegin(), run.rend());
    auto fwd = in_order(run), bwd = in_order(back);
    std::vector<EntryCandidate> out;
    const auto cap = static_cast<std::size_t>(std::max(1, opt_.max_candidates));
    for (std::size_t i = 0; out.size() < cap && (i < fwd.size() || i < bwd.size()); ++i) {
      if (i < fwd.size()) out.push_back(std::move(fwd[i].second));
      if (i < bwd.size() && out.size() < cap) out.push_back(std::move(bwd[i].second));
    }
    return out;
  }

 private:
  // Candidates for one order of the run with their total bridge length, shortest bridges first.
  std::vector<std::pair<double, EntryCandidate>> in_order(const std::vector<ContourId>& run) const {
    std::vector<std::pair<double, EntryCandidate>> out;
    for (const auto& first : first_entries(run[0], run[1])) {
      auto c = chain_from(first, run);
      if (!c) continue;
      bool duplicate = false;
      for (const auto& [len, other] : out) duplicate |= geometry::distance(other.pierce, c->second.pierce) < 0.5;
      if (!duplicate) out.push_back(std::move(*c));
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    return out;
  }

  // Entries into `a` near `b`: the standard candidates of a (corners first) that lie within the
  // gap limit of b, and entries where a comes closest to b (a few spots along the near stretch).
  std::vector<EntryCandidate> first_entries(ContourId a, ContourId b) const {
    std::vector<EntryCandidate> out;
    const Contour& cb = nest_.contours[b].source.contour;
    for (const auto& e : base_.segments[static_cast<std::size_t>(seg_of_[a.index()])].candidates) {
      if (e.fallback != Fallback::none) continue;
      if (geometry::distance(cb, e.point) <= opt_.max_gap_mm) out.push_back(e);
    }
    const Contour& ca = nest_.contours[a].source.contour;
    std::vector<std::pair<double, double>> near;  // (distance, s)
    for (const auto& q : samples(ca, sample_step(ca), nest_.contours[b].box.inflated(opt_.max_gap_mm))) {
      const double d = geometry::distance(cb, q.p);
      if (d <= opt_.max_gap_mm) near.emplace_back(d, q.s);
    }
    std::stable_sort(near.begin(), near.end());
    std::vector<double> taken;
    const bool cw = entries_.outer_clockwise;
    const double spacing = 10.0;  // [mm] spots closer than this along a give nearly the same chain
    for (const auto& [d, s] : near) {
      if (taken.size() >= 4) break;
      bool close = false;
      for (double t : taken) close |= std::abs(t - s) < spacing;
      if (close) continue;
      taken.push_back(s);
      if (auto e = planner_.entry_at(a, s, cw)) out.push_back(std::move(*e));
    }
    return out;
  }

  // The chain entered by `first`: each next contour reached by the shortest straight bridge from
  // where the previous one ends. nullopt when a bridge is too long or not clear.
  std::optional<std::pair<double, EntryCandidate>> chain_from(const EntryCandidate& first,
                                                              const std::vector<ContourId>& run) const {
    EntryCandidate c = first;
    c.pieces.clear();
    const bool cw = entries_.outer_clockwise;
    const std::size_t last = run.size() - 1;
    c.pieces.push_back({PieceKind::contour, run[0], planner_.whole_loop(run[0], first.s_mm, first.clockwise, last == 0), {}});
    Vec2 p = first.point;
    double s = first.s_mm;
    bool dir = first.clockwise;
    double bridges = 0;
    for (std::size_t i = 1; i <= last; ++i) {
      // The bridge ends on a vertex when the closest point lies within kerf/2 of one (as entries
      // do): else the next contour's cut starts and ends with a micrometre move there.
      const double s_next = planner_.at_vertex_if_near(run[i], planner_.closest(run[i], p).first);
      const Vec2 q = planner_.point_at(run[i], s_next);
      const double d = geometry::distance(p, q);
      if (d > opt_.max_gap_mm) return std::nullopt;
      Contour bridge{{geometry::Vertex{p, 0}, geometry::Vertex{q, 0}}, false};
      if (!planner_.bridge_clear(bridge, run[i - 1], run[i])) return std::nullopt;
      bridges += d;
      c.pieces.push_back({PieceKind::bridge, ContourId(), std::move(bridge), {}});
      c.pieces.push_back({PieceKind::contour, run[i], planner_.whole_loop(run[i], s_next, cw, i == last), {}});
      p = q;
      s = s_next;
      dir = cw;
    }
    c.lead_out = planner_.lead_out_at(run[last], s, dir);
    return std::pair{bridges, std::move(c)};
  }

  const Nest& nest_;
  const EntryPlanner& planner_;
  const CutJob& base_;
  const std::vector<std::int32_t>& seg_of_;
  const EntryOptions& entries_;
  const ChainOptions& opt_;
};

}  // namespace

std::vector<ChainLink> chain_links(const Nest& nest, const ChainOptions& options, int threads) {
  std::vector<ContourId> outers;
  std::vector<geometry::Box> boxes;
  for (std::size_t i = 0; i < nest.contours.size(); ++i) {
    const ContourId id(static_cast<std::int32_t>(i));
    if (nest.contours[id].role != ContourRole::outer) continue;
    outers.push_back(id);
    boxes.push_back(nest.contours[id].box);
  }
  const geometry::StaticSpatialIndex index(boxes);
  // Each outer's candidate neighbours, then the segment sets of those that have any, then the
  // gaps: each step dealt to the threads by outer, item i writing its own slot (the chain job of
  // 24 000 parts took 2.6 s on one thread). The links come out as one thread finds them.
  const std::size_t m = outers.size();
  std::vector<std::vector<std::uint32_t>> pairs(m);  // outer i -> later outers h within the gap, same parent
  deal(m, threads, 64, [&](std::size_t i) {
    std::vector<std::uint32_t> hits;
    index.query(boxes[i].inflated(options.max_gap_mm), hits);
    for (auto h : hits)
      // One inside the other's hole is no neighbour: a bridge would have to cross the hole.
      if (h > i && nest.contours[outers[i]].parent == nest.contours[outers[h]].parent) pairs[i].push_back(h);
  });
  std::vector<char> wanted(m, 0);
  for (std::size_t i = 0; i < m; ++i)
    for (auto h : pairs[i]) wanted[i] = wanted[h] = 1;
  std::vector<geometry::SegmentSet> sets(m);
  deal(m, threads, 64, [&](std::size_t k) {
    if (wanted[k]) sets[k] = geometry::make_segment_set(nest.contours[outers[k]].source.contour);
  });
  std::vector<std::vector<ChainLink>> found(m);
  deal(m, threads, 64, [&](std::size_t i) {
    for (auto h : pairs[i]) {
      const auto& a = nest.contours[outers[i]];
      const auto& b = nest.contours[outers[h]];
      const double gap = std::min(nearest(a.source.contour, sets[h], options.max_gap_mm).gap,
                                  nearest(b.source.contour, sets[i], options.max_gap_mm).gap);
      if (gap > 0 && gap <= options.max_gap_mm) found[i].push_back({outers[i], outers[h], gap});
    }
  });
  std::vector<ChainLink> out;
  for (auto& f : found) out.insert(out.end(), f.begin(), f.end());
  std::stable_sort(out.begin(), out.end(), [](const ChainLink& x, const ChainLink& y) {
    if (x.gap_mm != y.gap_mm) return x.gap_mm < y.gap_mm;
    return std::pair(x.a.value(), x.b.value()) < std::pair(y.a.value(), y.b.value());
  });
  return out;
}

CutJob make_chain_job(const Nest& nest, const EntryOptions& entries, const ChainOptions& options,
                      const CutJob* standard, const EntryPlanner* given, int threads) {
  std::optional<EntryPlanner> own_planner;
  if (!given) own_planner.emplace(nest, entries);
  const EntryPlanner& planner = given ? *given : *own_planner;
  CutJob own;
  if (!standard) own = make_cut_job(nest, planner, threads);
  const CutJob& base = standard ? *standard : own;
  std::vector<std::int32_t> seg_of(nest.contours.size(), -1);
  for (std::size_t k = 0; k < base.segments.size(); ++k) seg_of[base.segments[k].contours[0].index()] = static_cast<std::int32_t>(k);

  // Greedy runs from the closest pairs: a path through each run, no contour in two runs.
  const std::size_t n = nest.contours.size();
  Runs runs(n);
  std::vector<std::vector<ContourId>> adj(n);
  const auto max_len = static_cast<std::size_t>(std::max(2, options.max_contours));
  for (const auto& l : chain_links(nest, options, threads)) {
    const auto a = l.a.index(), b = l.b.index();
    if (adj[a].size() >= 2 || adj[b].size() >= 2 || runs.find(a) == runs.find(b)) continue;
    if (runs.size[runs.find(a)] + runs.size[runs.find(b)] > max_len) continue;
    adj[a].push_back(l.b);
    adj[b].push_back(l.a);
    runs.join(a, b);
  }
  std::vector<std::vector<ContourId>> chains;
  std::vector<char> seen(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    if (adj[i].size() != 1 || seen[i]) continue;
    std::vector<ContourId> run{ContourId(static_cast<std::int32_t>(i))};
    seen[i] = 1;
    for (ContourId prev, cur = run[0];;) {
      ContourId next;
      for (auto x : adj[cur.index()])
        if (x != prev) next = x;
      if (!next.valid() || seen[next.index()]) break;
      seen[next.index()] = 1;
      run.push_back(next);
      prev = cur;
      cur = next;
    }
    chains.push_back(std::move(run));
  }

  // Candidates per run (on the threads, run r into slot r); a run without any is shortened from
  // its end.
  const ChainBuilder builder(nest, planner, base, seg_of, entries, options);
  std::vector<std::optional<BasicSegment>> per_run(chains.size());
  deal(chains.size(), threads, 16, [&](std::size_t r) {
    auto& run = chains[r];
    while (run.size() >= 2) {
      auto cands = builder.candidates(run);
      if (!cands.empty()) {
        per_run[r] = BasicSegment{run, std::move(cands)};
        break;
      }
      run.pop_back();
    }
  });
  std::vector<BasicSegment> chain_segments;
  for (auto& s : per_run)
    if (s) chain_segments.push_back(std::move(*s));

  // Segments in the order of their first contour; chains that make the order cyclic are dropped,
  // the last formed first.
  for (;;) {
    std::vector<char> chained(n, 0);
    for (const auto& s : chain_segments)
      for (auto c : s.contours) chained[c.index()] = 1;
    CutJob job;
    job.diagnostics = base.diagnostics;
    std::vector<std::size_t> first_of(n, chain_segments.size());
    for (std::size_t k = 0; k < chain_segments.size(); ++k) {
      const auto& cs = chain_segments[k].contours;
      first_of[std::min_element(cs.begin(), cs.end(), [](ContourId x, ContourId y) { return x.value() < y.value(); })->index()] = k;
    }
    for (const auto& seg : base.segments) {
      const auto c = seg.contours[0].index();
      if (!chained[c]) job.segments.push_back(seg);
      else if (first_of[c] < chain_segments.size()) job.segments.push_back(chain_segments[first_of[c]]);
    }
    if (auto prec = segment_precedence(nest, job.segments)) {
      job.precedence = std::move(*prec);
      return job;
    }
    chain_segments.pop_back();  // never empty here: the standard job has no cycle
  }
}

}  // namespace cutroute::model
