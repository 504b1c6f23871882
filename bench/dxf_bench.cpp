// DXF reading time on the two large corpus nests (`cutroute inspect` must stay under 0.3 s on them).
#include <fstream>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>

#include <cutroute/io/dxf.hpp>

namespace {

const char* const kFiles[] = {"d2g_DRAAK.dxf", "vrs_Lv10_SHEET_001.dxf", "d2g_DRAAK.dxf"};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Whole read_dxf() from disk: pre-scan, dxflib, INSERT expansion, curve fitting.
void BM_ReadDxf(benchmark::State& state) {
  const std::string path = std::string(CUTROUTE_SHARED_DIR) + "/data/dxf/" + kFiles[state.range(0)];
  cutroute::io::DxfOptions opt;
  if (state.range(0) == 2) opt.units = "mm";  // DRAAK read as mm: 25.4 x fewer arcs to fit
  std::size_t vertices = 0;
  for (auto _ : state) {
    auto r = cutroute::io::read_dxf(path, opt);
    if (!r.ok()) {
      state.SkipWithError(cutroute::format(r.error()).c_str());
      return;
    }
    vertices = 0;
    for (const auto& e : r->entities) vertices += e.path.vertices.size();
    benchmark::DoNotOptimize(r);
  }
  state.SetLabel(std::string(kFiles[state.range(0)]) + (state.range(0) == 2 ? " (units mm)" : "") +
                 ", vertices " + std::to_string(vertices));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(slurp(path).size()));
}
BENCHMARK(BM_ReadDxf)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->MinTime(1.0);

}  // namespace
