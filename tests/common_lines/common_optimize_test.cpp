// `cutroute optimize` on nests of parts sharing edges: the written program re-parsed and checked
// (every edge cut, every part separated, holes first, shared stretches before the group's outline).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <cutroute/geometry/shapes.hpp>
#include <cutroute/io/nest_loader.hpp>

#include "common_program_check.hpp"
#include "support/dxf_builder.hpp"
#include "support/paths.hpp"

namespace cutroute::test {
namespace {

namespace fs = std::filesystem;
using geometry::Vec2;
using geometry::Vertex;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path temp_dir(const std::string& name) {
  auto d = fs::temp_directory_path() / ("cutroute-common-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

struct Layout {
  std::string dxf;
  double perimeters = 0;  // sum over every drawn contour [mm]
  double shared = 0;      // length of the stretches two parts share [mm]
};

// cols x rows rectangles of w x h drawn touching on a 1000 x 600 sheet, each with a round hole
// of radius r (none when r = 0). Shared length: (cols - 1) * rows * h + (rows - 1) * cols * w.
Layout grid(const fs::path& dir, int cols, int rows, double w, double h, double r) {
  DxfBuilder b;
  b.insunits(4);
  b.lwpolyline({Vertex{{0, 0}, 0}, Vertex{{1000, 0}, 0}, Vertex{{1000, 600}, 0}, Vertex{{0, 600}, 0}}, true, "SHEET");
  Layout l;
  const Vec2 o{100, 100};
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const double x = o.x + i * w, y = o.y + j * h;
      b.lwpolyline({Vertex{{x, y}, 0}, Vertex{{x + w, y}, 0}, Vertex{{x + w, y + h}, 0}, Vertex{{x, y + h}, 0}}, true,
                   "PARTS");
      l.perimeters += 2 * (w + h);
      if (r > 0) {
        b.circle({x + w / 2, y + h / 2}, r, "PARTS");
        l.perimeters += 2 * std::numbers::pi * r;
      }
    }
  l.shared = (cols - 1) * rows * h + (rows - 1) * cols * w;
  l.dxf = (dir / "grid.dxf").string();
  std::ofstream(l.dxf) << b.str();
  return l;
}

struct OptRun {
  CommandOutput cmd;
  std::string program;
};

OptRun optimize(const std::string& dxf, const fs::path& dir, const std::string& extra) {
  OptRun r;
  const auto prog = dir / "out.ngc";
  r.cmd = run_command(cli_path() + " optimize " + dxf + " -o " + prog.string() + " --quiet --time-limit 1 " + extra);
  if (r.cmd.exit_code == 0) r.program = slurp(prog);
  return r;
}

model::Nest load(const std::string& dxf) {
  auto loaded = io::load_nest(dxf, io::NestLoadOptions{});
  EXPECT_TRUE(loaded.ok());
  return loaded->nest;
}

// Today's standard technique on the same nest, as the baseline: each part's outline cut whole,
// so the shared edges are cut twice and the boundary cut length is the sum of the perimeters.
TEST(CommonOptimize, StandardCutsSharedEdgesTwice) {
  const auto dir = temp_dir("standard");
  const Layout l = grid(dir, 3, 2, 120, 80, 15);
  const OptRun run = optimize(l.dxf, dir, "");
  ASSERT_EQ(run.cmd.exit_code, 0) << run.cmd.err;
  const auto check = check_common_program(load(l.dxf), run.program, 0.005);
  for (const auto& f : check.failures) ADD_FAILURE() << f;
  EXPECT_NEAR(check.boundary_cut_mm, l.perimeters, 0.01);
  EXPECT_EQ(check.runs, 12);
}

}  // namespace
}  // namespace cutroute::test
