// GTSPLIB reader: weight formats, distance functions, header quirks, and values of shared instances.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <cutroute/io/instance.hpp>
#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/solution.hpp>
#include <cutroute/solve/solve.hpp>

#include "support/paths.hpp"

namespace cutroute::io {
namespace {

using solve::NodeId;

std::string gtsp_header(const std::string& weights) {
  return "NAME : t\nTYPE : AGTSP\nDIMENSION : 3\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE : EXPLICIT\n" + weights + "GTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\nEOF\n";
}

solve::Cost c(const solve::Problem& p, int a, int b) { return p.arc_cost(NodeId(a - 1), NodeId(b - 1)); }

TEST(InstanceGtsp, ExplicitWeightFormats) {
  // Symmetric matrix [[0 1 2] [1 0 3] [2 3 0]] written in every triangular format.
  const std::pair<const char*, const char*> cases[] = {
      {"FULL_MATRIX", "0 1 2\n1 0 3\n2 3 0\n"}, {"UPPER_ROW", "1 2\n3\n"},        {"LOWER_ROW", "1\n2 3\n"},
      {"UPPER_DIAG_ROW", "0 1 2 0 3 0\n"},      {"LOWER_DIAG_ROW", "0 1 0 2 3 0\n"}};
  for (auto [fmt, data] : cases) {
    auto r = parse_instance(gtsp_header(std::string("EDGE_WEIGHT_FORMAT : ") + fmt + "\nEDGE_WEIGHT_SECTION\n" + data), "t.gtsp");
    ASSERT_TRUE(r.ok()) << fmt << ": " << r.error().message;
    const auto& p = r->problem;
    EXPECT_EQ(c(p, 1, 2), 1) << fmt;
    EXPECT_EQ(c(p, 2, 1), 1) << fmt;
    EXPECT_EQ(c(p, 1, 3), 2) << fmt;
    EXPECT_EQ(c(p, 3, 2), 3) << fmt;
    EXPECT_EQ(p.cluster_count(), 2);
    EXPECT_EQ(p.cluster_of(NodeId(2)), solve::ClusterId(1));
    EXPECT_TRUE(p.closed());
  }
}

TEST(InstanceGtsp, DistanceFunctionsMatchTsplib) {
  auto coords = [](const char* type, const char* a, const char* b) {
    return std::string("NAME: d\nTYPE: GTSP\nDIMENSION: 2\nGTSP_SETS: 2\nEDGE_WEIGHT_TYPE: ") + type +
           "\nNODE_COORD_SECTION\n1 " + a + "\n2 " + b + "\nGTSP_SET_SECTION\n1 1 -1\n2 2 -1\nEOF\n";
  };
  // EUC_2D rounds (3-4-5 triangle scaled: 2.5 -> 3? nint(sqrt(6.25)) = nint(2.5) = 3), CEIL_2D ceils.
  EXPECT_EQ(c(parse_instance(coords("EUC_2D", "0 0", "1.5 2"), "x.gtsp")->problem, 1, 2), 3);
  EXPECT_EQ(c(parse_instance(coords("EUC_2D", "0 0", "1 1"), "x.gtsp")->problem, 1, 2), 1);
  EXPECT_EQ(c(parse_instance(coords("CEIL_2D", "0 0", "1 1"), "x.gtsp")->problem, 1, 2), 2);
  // ATT: sqrt((100^2 + 0) / 10) = 31.62 -> 32 (rounded up when the nearest integer is below).
  EXPECT_EQ(c(parse_instance(coords("ATT", "0 0", "100 0"), "x.gtsp")->problem, 1, 2), 32);
  // GEO: one degree of latitude on TSPLIB's sphere (6378.388 km, PI = 3.141592) is 111.3 km -> 112.
  EXPECT_EQ(c(parse_instance(coords("GEO", "10.00 20.00", "11.00 20.00"), "x.gtsp")->problem, 1, 2), 112);
}

// Above 3000 nodes EUC_2D is computed from the points (PlanarCosts) instead of a matrix: the same
// nint(distance) as TSPLIB defines it, symmetric, on a generated instance (coordinates with halves so
// that the rounding is exercised) and on the corpus file 31C3k.0.
TEST(InstanceGtsp, LargeEuc2dUsesPlanarCostsWithTsplibRounding) {
  const int n = 3010;
  std::string text = "NAME: big\nTYPE: GTSP\nDIMENSION: " + std::to_string(n) + "\nGTSP_SETS: 2\nEDGE_WEIGHT_TYPE: EUC_2D\nNODE_COORD_SECTION\n";
  std::vector<std::pair<double, double>> pts;
  for (int i = 0; i < n; ++i) {
    pts.emplace_back((i * 37 % 1001) * 0.5, (i * 91 % 773) * 1.5);
    text += std::to_string(i + 1) + " " + std::to_string(pts.back().first) + " " + std::to_string(pts.back().second) + "\n";
  }
  text += "GTSP_SET_SECTION\n1";
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on " " + std::to_string(i).
  for (int i = 1; i <= n / 2; ++i) text.append(" ").append(std::to_string(i));
  text += " -1\n2";
  for (int i = n / 2 + 1; i <= n; ++i) text.append(" ").append(std::to_string(i));
  text += " -1\nEOF\n";
  auto r = parse_instance(text, "big.gtsp");
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto& p = r->problem;
  ASSERT_NE(p.planar(), nullptr);
  EXPECT_TRUE(p.symmetric());
  for (int a = 0; a < n; a += 97)
    for (int b = 1; b < n; b += 131) {
      if (a == b) continue;
      const double dx = pts[static_cast<std::size_t>(a)].first - pts[static_cast<std::size_t>(b)].first;
      const double dy = pts[static_cast<std::size_t>(a)].second - pts[static_cast<std::size_t>(b)].second;
      const auto expected = static_cast<solve::Cost>(std::floor(std::sqrt(dx * dx + dy * dy) + 0.5));
      ASSERT_EQ(p.arc_cost(NodeId(a), NodeId(b)), expected) << a << " " << b;
    }
  // 31C3k.0: node 1 (492189 676982) to node 2 (996275 623342): 506931.89 -> 506932.
  auto corpus = read_instance(test::shared("data/gtsplib/31C3k.0.gtsp"));
  ASSERT_TRUE(corpus.ok()) << corpus.error().message;
  EXPECT_NE(corpus->problem.planar(), nullptr);
  EXPECT_EQ(c(corpus->problem, 1, 2), 506932);
  EXPECT_EQ(c(corpus->problem, 2, 1), 506932);
}

TEST(InstanceGtsp, HeaderQuirksOfTheCorpus) {
  // "TYPE  AGTSP" without a colon, "TYPE : GTSP (M.~Hofmeister)", "EDGE_WEIGHT_TYPE:  EXPLICIT".
  for (const char* type : {"TYPE  AGTSP", "TYPE : GTSP (M.~Hofmeister)"}) {
    const std::string text = std::string("NAME : q\n") + type +
                             "\nDIMENSION : 2\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE:  EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX \n"
                             "EDGE_WEIGHT_SECTION\n 9999 5\n 6 9999\nGTSP_SET_SECTION\n1 1 -1\n2 2 -1\n";
    auto r = parse_instance(text, "q.txt");
    ASSERT_TRUE(r.ok()) << type << ": " << r.error().message;
    EXPECT_EQ(r->format, InstanceFormat::gtsp);
    EXPECT_EQ(c(r->problem, 1, 2), 5);
    EXPECT_EQ(c(r->problem, 2, 1), 6);
  }
}

TEST(InstanceGtsp, LineEndingsDoNotMatter) {
  const std::string lf = gtsp_header("EDGE_WEIGHT_FORMAT : UPPER_ROW\nEDGE_WEIGHT_SECTION\n1 2\n3\n");
  std::string crlf, cr;
  for (char ch : lf) {
    crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
    cr += ch == '\n' ? '\r' : ch;
  }
  for (const auto& text : {lf, crlf, cr}) {
    auto r = parse_instance(text, "t.gtsp");
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(c(r->problem, 2, 3), 3);
  }
}

// Shared GTSPLIB files whose optimum (../shared/data/gtsplib/README.md) the DP proves quickly.
TEST(InstanceGtsp, SmallGtsplibInstancesSolveToTheirKnownOptimum) {
  const std::pair<const char*, solve::Cost> known[] = {{"3burma14", 1805}, {"4br17", 31},   {"5gr24", 334},
                                                       {"6bays29", 822},   {"10att48", 5394}, {"11eil51", 174}};
  for (auto [name, opt] : known) {
    auto r = read_instance(test::shared(std::string("data/gtsplib/") + name + ".gtsp"));
    ASSERT_TRUE(r.ok()) << name << ": " << r.error().message;
    const auto s = solve::solve_exact(r->problem, std::size_t{1} << 30, StopToken{});
    EXPECT_EQ(s.status, solve::SolveStatus::optimal) << name;
    EXPECT_EQ(s.cost, opt) << name;
    EXPECT_TRUE(solve::validate(r->problem, s).empty()) << name;
  }
}

// The runs that stayed around one local optimum for their whole length before epochs (docs/SOLVER.md):
// 35ftv170 seed 5 ended at 1247 (+3.5 %), 87gr431 seed 4 at 103272 (+1.3 %), both with 2 threads.
// With the automatic settings (epochs of 3 rounds) both reach the optimum.
TEST(InstanceGtsp, HeuristicLeavesTheLocalOptimaItStayedInBeforeEpochs) {
  const std::tuple<const char*, std::uint64_t, solve::Cost> runs[] = {{"35ftv170", 5, 1205}, {"87gr431", 4, 101946}};
  for (auto [name, seed, opt] : runs) {
    auto r = read_instance(test::shared(std::string("data/gtsplib/") + name + ".gtsp"));
    ASSERT_TRUE(r.ok()) << name << ": " << r.error().message;
    solve::SolveParams sp;
    sp.solver = solve::SolverKind::heuristic;
    sp.seed = seed;
    sp.threads = 2;
    sp.time_limit_s = 0;
    const auto s = solve::solve(r->problem, sp);
    EXPECT_TRUE(solve::validate(r->problem, s).empty()) << name;
    EXPECT_EQ(s.cost, opt) << name << " seed " << seed;
  }
}

TEST(InstanceGtsp, EveryCorpusFileParses) {
  // Only the headers' claims: clusters and nodes as in the file name / DIMENSION.
  const std::pair<const char*, int> files[] = {{"35ftv170", 35}, {"35si175", 35}, {"49usa1097", 49}, {"107si535", 107}, {"200dsj1000", 200}};
  for (auto [name, clusters] : files) {
    auto r = read_instance(test::shared(std::string("data/gtsplib/") + name + ".gtsp"));
    ASSERT_TRUE(r.ok()) << name << ": " << r.error().message;
    EXPECT_EQ(r->problem.cluster_count(), clusters) << name;
  }
}

}  // namespace
}  // namespace cutroute::io
