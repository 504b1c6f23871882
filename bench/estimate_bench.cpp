// Reading a generated 1 000 000-block cutting program (issue 3: estimate must take under 1 s).
#include <benchmark/benchmark.h>

#include <charconv>
#include <string>

#include <cutroute/nc/gcode_reader.hpp>

namespace {

void append_fixed(std::string& out, char letter, double v) {
  char buf[32];
  buf[0] = letter;
  const auto r = std::to_chars(buf + 1, buf + sizeof buf, v, std::chars_format::fixed, 3);
  out.append(buf, r.ptr);
}

// Rounded-rectangle contours with arc corners (I/J), 12 blocks each, on a 3000 x 1500 sheet.
std::string make_program(std::size_t blocks) {
  std::string p = "G21 G90 G17\nF6000\n";
  p.reserve(blocks * 28);
  std::size_t n = 2;
  for (std::size_t k = 0; n + 13 < blocks; ++k) {
    const double x = 10.0 + static_cast<double>(k % 140) * 20.0;
    const double y = 10.0 + static_cast<double>((k / 140) % 70) * 20.0;
    const double w = 12.0, h = 8.0, r = 2.0;
    const auto line = [&](const char* g, double ax, double ay) {
      p += g;
      append_fixed(p, 'X', ax);
      p += ' ';
      append_fixed(p, 'Y', ay);
    };
    line("G0 ", x + r, y);
    p += "\nM3\n";
    line("G1 ", x + w - r, y);
    p += '\n';
    line("G3 ", x + w, y + r);
    p += " I0 J2.000\n";
    line("G1 ", x + w, y + h - r);
    p += '\n';
    line("G3 ", x + w - r, y + h);
    p += " I-2.000 J0\n";
    line("G1 ", x + r, y + h);
    p += '\n';
    line("G3 ", x, y + h - r);
    p += " I0 J-2.000\n";
    line("G1 ", x, y + r);
    p += '\n';
    line("G3 ", x + r, y);
    p += " I2.000 J0\n";
    p += "M5\n(contour end)\n";
    n += 11;
  }
  while (n + 1 < blocks) {
    p += "G0 X0 Y0\n";
    ++n;
  }
  p += "M30\n";
  return p;
}

void BM_ReadGcode1M(benchmark::State& state) {
  const std::string program = make_program(static_cast<std::size_t>(state.range(0)));
  const cutroute::nc::ReadOptions opt;
  std::size_t frames = 0;
  for (auto _ : state) {
    auto r = cutroute::nc::read_gcode(program, "bench.nc", opt);
    if (!r.ok()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    frames = r->frames;
    benchmark::DoNotOptimize(r->cut_length_mm);
  }
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["MB"] = static_cast<double>(program.size()) / 1e6;
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(program.size()));
}
BENCHMARK(BM_ReadGcode1M)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
