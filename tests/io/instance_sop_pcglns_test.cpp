// SOP and PCGLNS readers, the tiny instances of data/instances/, and malformed files (line numbers).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <cutroute/io/instance.hpp>
#include <cutroute/solve/exact_dp.hpp>
#include <cutroute/solve/solve.hpp>

#include "support/paths.hpp"

namespace cutroute::io {
namespace {

using solve::ClusterId;
using solve::NodeId;


std::string instances_dir() { return std::string(CUTROUTE_INSTANCES_DIR) + "/"; }

solve::Cost stated_optimum(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  // A plain search, not <regex>: GCC 12 warns (falsely) inside std::regex at -O1 (sanitized build).
  const std::string text = ss.str();
  const auto at = text.find("optimum ");
  if (at == std::string::npos) return -1;
  const auto digits = at + 8;
  const auto end = text.find_first_not_of("0123456789", digits);
  if (end == digits) return -1;
  return std::stoll(text.substr(digits, end - digits));
}

TEST(InstanceFiles, TinyInstancesSolveToTheirStatedOptimum) {
  for (const char* name : {"tiny.gtsp", "tiny.pcglns", "tiny.sop"}) {
    const std::string path = instances_dir() + name;
    auto r = read_instance(path);
    ASSERT_TRUE(r.ok()) << name << ": " << r.error().message;
    const solve::Cost opt = stated_optimum(path);
    ASSERT_GT(opt, 0) << name;
    const auto ex = solve::solve_exact(r->problem, std::size_t{1} << 30, StopToken{});
    EXPECT_EQ(ex.status, solve::SolveStatus::optimal) << name;
    EXPECT_EQ(ex.cost, opt) << name;
    solve::SolveParams hp;
    hp.solver = solve::SolverKind::heuristic;
    hp.threads = 1;
    EXPECT_EQ(solve::solve(r->problem, hp).cost, opt) << name;
  }
}

TEST(InstanceSop, MinusOneIsPrecedenceAndPathRunsFromFirstToLast) {
  auto r = read_instance(instances_dir() + "tiny.sop");
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto& p = r->problem;
  EXPECT_EQ(r->format, InstanceFormat::sop);
  EXPECT_FALSE(p.closed());
  EXPECT_EQ(p.start_cluster(), ClusterId(0));
  EXPECT_EQ(p.cluster_count(), 6);
  EXPECT_TRUE(p.must_precede(ClusterId(2), ClusterId(1)));  // c[2][3] = -1: node 3 before node 2
  EXPECT_TRUE(p.must_precede(ClusterId(3), ClusterId(5)));  // everything before node 6
  EXPECT_TRUE(p.forbidden(NodeId(1), NodeId(2)));
}

TEST(InstancePcglns, ForbiddenArcsOrderingAndStartGroup) {
  auto r = read_instance(instances_dir() + "tiny.pcglns");
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto& p = r->problem;
  EXPECT_EQ(r->format, InstanceFormat::pcglns);
  EXPECT_TRUE(p.closed());
  EXPECT_EQ(p.start_cluster(), ClusterId(1));
  EXPECT_TRUE(p.forbidden(NodeId(0), NodeId(6)));  // entry (1, 7) is -1
  EXPECT_TRUE(p.forbidden(NodeId(2), NodeId(4)));
  EXPECT_FALSE(p.forbidden(NodeId(4), NodeId(2)));
  EXPECT_TRUE(p.must_precede(ClusterId(0), ClusterId(3)));  // 1 before 3 before 4
  const auto s = solve::solve(p, solve::SolveParams{});
  ASSERT_FALSE(s.route.empty());
  EXPECT_EQ(p.cluster_of(s.route[0]), ClusterId(1));
}

TEST(InstancePcglns, OrderingLineWithSeveralSuccessors) {
  const std::string text =
      "NAME : m\nTYPE : PCGLNS\nDIMENSION : 4\nGTSP_SETS : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\n"
      "EDGE_WEIGHT_SECTION\n0 1 1 1\n1 0 1 1\n1 1 0 1\n1 1 1 0\nGTSP_SET_SECTION\n1 1 -1\n2 2 -1\n3 3 -1\n4 4 -1\n"
      "GTSP_SET_ORDERING\n2 3 4 -1\nSTART_GROUP_SECTION\n1\nEOF\n";
  auto r = parse_instance(text, "m.pcglns");
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->problem.must_precede(ClusterId(1), ClusterId(2)));
  EXPECT_TRUE(r->problem.must_precede(ClusterId(1), ClusterId(3)));
  EXPECT_FALSE(r->problem.must_precede(ClusterId(2), ClusterId(3)));
}

// One defect per case: the message must hold `message` and name `line` (none when 0).
struct BadInstance {
  const char* what;
  std::string text;
  long line;
  const char* message;
};

void expect_errors(const std::vector<BadInstance>& cases, const std::string& file) {
  for (const auto& c : cases) {
    auto r = parse_instance(c.text, file);
    ASSERT_FALSE(r.ok()) << c.what;
    EXPECT_NE(r.error().message.find(c.message), std::string::npos) << c.what << ": " << r.error().message;
    EXPECT_EQ(r.error().file, file) << c.what;
    if (c.line > 0) {
      ASSERT_TRUE(r.error().line.has_value()) << c.what;
      EXPECT_EQ(*r.error().line, c.line) << c.what << ": " << format(r.error());
    }
  }
}

TEST(InstanceErrors, MalformedFilesGiveLineNumbers) {
  const std::string good_head = "NAME : b\nTYPE : GTSP\nDIMENSION : 3\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE : EUC_2D\n";  // lines 1-5
  expect_errors({
      {"bad coordinate", good_head + "NODE_COORD_SECTION\n1 0 0\n2 x 0\n3 1 1\nGTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n", 8, "expected a number"},
      {"node id out of range", good_head + "NODE_COORD_SECTION\n1 0 0\n2 1 0\n3 1 1\nGTSP_SET_SECTION\n1 1 -1\n2 2 9 -1\n", 12, "node 9"},
      {"truncated coordinates", good_head + "NODE_COORD_SECTION\n1 0 0\n2 1 0\nGTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n", 9, "ended early"},
      {"bad dimension", "NAME : b\nTYPE : GTSP\nDIMENSION : -3\n", 3, "DIMENSION"},
      {"unknown metric", "NAME : b\nTYPE : GTSP\nDIMENSION : 3\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE : SPHERE\nNODE_COORD_SECTION\n1 0 0\n2 1 0\n3 1 1\n"
                         "GTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n", 5, "unsupported EDGE_WEIGHT_TYPE"},
      {"node in two sets", good_head + "NODE_COORD_SECTION\n1 0 0\n2 1 0\n3 1 1\nGTSP_SET_SECTION\n1 1 2 -1\n2 2 3 -1\nEOF\n", 12,
       "node 2 is in set 1 and in set 2"},
      {"stray number", "NAME : b\n42\n", 2, "outside of any section"},
      // Found by fuzzing: a second DIMENSION after the coordinates read past them (ASan).
      {"dimension given again", good_head + "NODE_COORD_SECTION\n1 0 0\n2 1 0\n3 1 1\nDIMENSION : 5\nGTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n", 10,
       "DIMENSION given twice"},
      // Found by fuzzing: distances of such points overflowed the int64 conversion (UBSan, above 3000 nodes).
      {"huge coordinate", good_head + "NODE_COORD_SECTION\n1 0 0\n2 1e200 0\n3 1 1\nGTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n", 8, "coordinate beyond +-1e11"}},
                "bad.gtsp");
  auto missing = read_instance("/nonexistent/x.gtsp");
  EXPECT_FALSE(missing.ok());
}

// Defects of the explicit-matrix formats the fuzzer found; each was read silently, crashed or took
// gigabytes before.
TEST(InstanceErrors, MalformedPcglnsFilesGiveLineNumbers) {
  const std::string head = "NAME : b\nTYPE : PCGLNS\nDIMENSION : 3\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
                           "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n";  // lines 1-7
  const std::string matrix = "0 1 2\n1 0 3\n2 3 0\n";                                  // lines 8-10
  const std::string sets = "GTSP_SET_SECTION\n1 1 -1\n2 2 3 -1\n";                     // lines 11-13
  expect_errors({
      {"a row too many", head + matrix + "4 4 4\n" + sets, 11, "more edge weights than the format FULL_MATRIX holds"},
      {"DIMENSION again after the matrix", head + matrix + "DIMENSION : 9\n" + sets, 11, "DIMENSION given twice"},
      {"GTSP_SETS again after the sets", head + matrix + sets + "GTSP_SETS : 9\n", 14, "GTSP_SETS given twice"},
      // 12 000 nodes declared, one weight given: refused before the 1.15-GB matrix is allocated.
      {"large DIMENSION, short section",
       "NAME : b\nTYPE : PCGLNS\nDIMENSION : 12000\nGTSP_SETS : 1\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_SECTION\n0\nEOF\n", 8,
       "gives 1 of the 144000000 weights FULL_MATRIX needs"},
      {"short section", head + "0 1 2\n1 0\n" + sets, 10, "gives 5 of the 9 weights"},
      // 4294967298 - 1 wrapped to cluster 1 when cast to int.
      {"ordering id beyond int", "NAME : b\nTYPE : PCGLNS\nGTSP_SET_ORDERING\n4294967298 4294967299 -1\n", 4,
       "set id 4294967298 does not exist"},
      {"ordering before GTSP_SETS names a missing set",
       "NAME : b\nTYPE : PCGLNS\nGTSP_SET_ORDERING\n1 5 -1\nDIMENSION : 3\nGTSP_SETS : 2\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
       "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n" + matrix + sets + "EOF\n",
       4, "set id 5 does not exist (GTSP_SETS is 2)"},
      // Found by fuzzing (session 39): each came from ProblemBuilder::build() without a line, with
      // 0-based ids ("node 0 is in clusters 0 and 0", "cluster 2 must precede the start cluster 0").
      {"a node twice in one set", head + matrix + "GTSP_SET_SECTION\n1 1 1 -1\n2 2 3 -1\n", 12, "set 1 names node 1 twice"},
      {"an empty set", head + matrix + "GTSP_SET_SECTION\n1 1 2 3 -1\n2 -1\n", 13, "set 2 is empty"},
      {"a node in no set", head + matrix + "GTSP_SET_SECTION\n1 1 -1\n2 2 -1\n", 11, "node 3 is in no set"},
      {"a set before itself", head + matrix + sets + "GTSP_SET_ORDERING\n2 2 -1\n", 15, "set 2 must come before itself"},
      {"a set before the start set", head + matrix + sets + "GTSP_SET_ORDERING\n2 1 -1\n", 15,
       "set 2 must come before set 1, which is the start set"},
      // 4 arcs of 2^40 cost more than one forbidden arc (2^41): the heuristic took the forbidden one.
      {"weights too large next to forbidden arcs",
       "NAME : b\nTYPE : PCGLNS\nDIMENSION : 4\nGTSP_SETS : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\n"
       "EDGE_WEIGHT_SECTION\n0 1099511627776 -1 -1\n-1 0 1099511627776 -1\n-1 -1 0 1099511627776\n1099511627776 -1 -1 0\n"
       "GTSP_SET_SECTION\n1 1 -1\n2 2 -1\n3 3 -1\n4 4 -1\n",
       8, "weights up to 549755813887 are supported"}},
                "bad.pcglns");
  // An ordering cycle is reported at the line of one of its pairs.
  {
    const std::string text = head.substr(0, head.find("DIMENSION")) +
                             "DIMENSION : 4\nGTSP_SETS : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n"
                             "0 1 2 3\n1 0 3 4\n2 3 0 5\n3 4 5 0\nGTSP_SET_SECTION\n1 1 -1\n2 2 -1\n3 3 -1\n4 4 -1\n"
                             "GTSP_SET_ORDERING\n2 3 -1\n3 4 -1\n4 2 -1\n";  // the pairs on lines 18-20
    auto r = parse_instance(text, "cycle.pcglns");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("the order has a cycle: set 2 before set 3 before set 4 before set 2"), std::string::npos)
        << r.error().message;
    ASSERT_TRUE(r.error().line.has_value());
    EXPECT_GE(*r.error().line, 18);
    EXPECT_LE(*r.error().line, 20);
  }
  // The same file without the defects reads, also after a UTF-8 byte order mark (Windows editors).
  auto good = parse_instance(head + matrix + sets + "GTSP_SET_ORDERING\n1 2 -1\nSTART_GROUP_SECTION\n1\nEOF\n", "good.pcglns");
  ASSERT_TRUE(good.ok()) << format(good.error());
  auto bom = parse_instance("\xEF\xBB\xBF" + head + matrix + sets + "EOF\n", "bom.pcglns");
  ASSERT_TRUE(bom.ok()) << format(bom.error());
}

// SOP precedences are the -1 entries (row i, column j: node j before node i); the ones that cannot
// hold are named at their line, with the file's node numbers.
TEST(InstanceErrors, ImpossibleSopPrecedencesGiveLineNumbers) {
  const std::string head = "NAME : s\nTYPE : SOP\nDIMENSION : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\n"
                           "EDGE_WEIGHT_SECTION\n4\n";  // lines 1-7, the rows on 8-11
  expect_errors({
      {"a node before the first", head + "0 -1 1 1\n-1 0 1 1\n-1 1 0 1\n-1 -1 -1 0\nEOF\n", 8,
       "node 2 must come before node 1, which starts the path"},
      {"the last node before another", head + "0 1 1 1\n-1 0 1 -1\n-1 1 0 1\n-1 -1 -1 0\nEOF\n", 9,
       "node 4 must come before node 2, but node 4 ends the path"},
      {"a cycle", head + "0 1 1 1\n-1 0 -1 1\n-1 -1 0 1\n-1 -1 -1 0\nEOF\n", 0,
       "the order has a cycle: node 2 before node 3 before node 2"},
      {"-1 in a symmetric format (both directions)",
       "NAME : s\nTYPE : SOP\nDIMENSION : 4\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : UPPER_ROW\nEDGE_WEIGHT_SECTION\n4\n1 1 1\n-1 1\n1\nEOF\n",
       9, "the order has a cycle: node 2 before node 3 before node 2"}},
                "bad.sop");
  auto good = parse_instance(head + "0 1 1 1\n-1 0 1 1\n-1 -1 0 1\n-1 -1 -1 0\nEOF\n", "good.sop");
  ASSERT_TRUE(good.ok()) << format(good.error());
  // Read by its name as a GTSP, an SOP would lose its precedences.
  auto renamed = parse_instance(head + "0 1 1 1\n-1 0 1 1\n-1 -1 0 1\n-1 -1 -1 0\nEOF\n", "good.gtsp");
  ASSERT_FALSE(renamed.ok());
  EXPECT_EQ(renamed.error().line, 2);
  EXPECT_NE(renamed.error().message.find("TYPE is SOP, but the file is read as .gtsp"), std::string::npos) << renamed.error().message;
}

}  // namespace
}  // namespace cutroute::io
