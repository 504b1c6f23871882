// GTSPLIB reader: weight formats, distance functions, header quirks, and values of shared instances.
#include <gtest/gtest.h>

#include <cutroute/io/instance.hpp>
#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/solution.hpp>

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
