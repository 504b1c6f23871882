// report_svg(): the cost map CT(vc, Vf) on log axes, like the seed's Figs. 1-2.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <cutroute/machining/contours.hpp>
#include <cutroute/machining/report.hpp>

#include "machining/format.hpp"

namespace cutroute::machining {

namespace {

// Plot frame in SVG user units.
constexpr double kWidth = 1000, kHeight = 700;
constexpr double kLeft = 90, kTop = 70, kPlotW = 640, kPlotH = 540;
constexpr int kMaxCells = 90;  // heat-map cells per axis: keeps the file small and readable

struct Rgb {
  double r, g, b;
};

// Viridis-like ramp, t = 0 cheap (yellow) ... t = 1 expensive (purple).
Rgb ramp(double t) {
  static const Rgb stops[] = {{253, 231, 37}, {94, 201, 98}, {33, 145, 140}, {59, 82, 139}, {68, 1, 84}};
  // NaN (a flat cost surface: 0 / 0 in shade()) would pass std::clamp and index past the stops.
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) * 4.0 : 0.0;
  const int k = std::min(3, static_cast<int>(t));
  const double u = t - k;
  return {stops[k].r + (stops[k + 1].r - stops[k].r) * u, stops[k].g + (stops[k + 1].g - stops[k].g) * u,
          stops[k].b + (stops[k + 1].b - stops[k].b) * u};
}
std::string css(Rgb c) {
  const auto h = [](double v) {
    static const char* d = "0123456789abcdef";
    const int x = std::clamp(static_cast<int>(std::lround(v)), 0, 255);
    return std::string{d[x / 16], d[x % 16]};
  };
  std::string out = "#";
  out += h(c.r);
  out += h(c.g);
  out += h(c.b);
  return out;
}
Rgb pale(Rgb c) { return {c.r * 0.3 + 225 * 0.7, c.g * 0.3 + 225 * 0.7, c.b * 0.3 + 225 * 0.7}; }

std::string esc(const std::string& s) {
  std::string o;
  for (char ch : s) {
    if (ch == '<')
      o += "&lt;";
    else if (ch == '>')
      o += "&gt;";
    else if (ch == '&')
      o += "&amp;";
    else if (ch == '"')
      o += "&quot;";
    else
      o += ch;
  }
  return o;
}

struct Axes {
  double lx0, lx1, ly0, ly1;  // log ranges
  double x(double vc) const { return kLeft + (std::log(vc) - lx0) / (lx1 - lx0) * kPlotW; }
  double y(double vf) const { return kTop + kPlotH - (std::log(vf) - ly0) / (ly1 - ly0) * kPlotH; }
};

std::string xy(double x, double y) { return fmt_fixed(x, 2) + "," + fmt_fixed(y, 2); }

// 1-2-5 ticks inside [lo, hi] (finer when the range is short).
std::vector<double> log_ticks(double lo, double hi) {
  if (!(lo > 0.0 && std::isfinite(hi) && hi >= lo)) return {};  // log10(0) cast to int is undefined
  for (const auto& mant : {std::vector<double>{1, 2, 5}, std::vector<double>{1, 1.5, 2, 3, 5, 7}}) {
    std::vector<double> t;
    for (int e = static_cast<int>(std::floor(std::log10(lo))) - 1;
         e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
      for (double m : mant) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
      }
    }
    if (t.size() >= 3) return t;
  }
  return {lo, hi};
}

double at_index(const std::vector<double>& g, double t) {
  if (g.size() < 2) return g.front();
  return g.front() * std::pow(g.back() / g.front(), t / static_cast<double>(g.size() - 1));
}

}  // namespace

std::string report_svg(const RunOutput& out) {
  const Problem& p = *out.problem;
  const OptimizeResult& r = *out.result;
  std::string s;
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt_fixed(kWidth, 0) + "\" height=\"" +
       fmt_fixed(kHeight, 0) + "\" viewBox=\"0 0 " + fmt_fixed(kWidth, 0) + " " + fmt_fixed(kHeight, 0) +
       "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"13\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const std::string title = "Cost per part CT(vc, Vf)" + (p.name.empty() ? std::string() : " - " + p.name);
  s += "<text x=\"" + fmt_fixed(kLeft, 0) + "\" y=\"28\" font-size=\"16\" font-weight=\"bold\">" +
       esc(title) + "</text>\n";
  if (!r.surface || r.surface->vc.size() < 2 || r.surface->f.size() < 2) {
    s += "<text x=\"" + fmt_fixed(kLeft, 0) + "\" y=\"60\">status: " + std::string(to_string(r.status)) +
         (r.infeasible ? " - " + esc(r.infeasible->message) : std::string()) + "</text>\n</svg>\n";
    return s;
  }
  const Surface& g = *r.surface;
  const int nx = static_cast<int>(g.vc.size()), ny = static_cast<int>(g.f.size());
  const auto vf = [&](double vc, double f) { return feed_speed_mm_min(f, spindle_speed_rpm(vc, p.op.D)); };
  Axes ax{std::log(g.vc.front()), std::log(g.vc.back()), std::log(vf(g.vc.front(), g.f.front())),
          std::log(vf(g.vc.back(), g.f.back()))};
  // A feed speed of 0 (a bore so wide the spindle barely turns) has no place on log axes.
  if (!(std::isfinite(ax.lx0) && std::isfinite(ax.lx1) && std::isfinite(ax.ly0) && std::isfinite(ax.ly1) && ax.lx1 > ax.lx0 &&
        ax.ly1 > ax.ly0)) {
    s += "<text x=\"" + fmt_fixed(kLeft, 0) + "\" y=\"60\">status: " + std::string(to_string(r.status)) +
         " - no plot: the search box's feed speeds are not positive finite numbers</text>\n</svg>\n";
    return s;
  }
  // Over the finite costs only: a grid reaching into overflow (f = 1e-160 mm/rev) holds NaN and inf,
  // which std::min_element / max_element do not skip.
  double ct_lo = std::numeric_limits<double>::infinity(), ct_hi = -ct_lo;
  for (double ct : g.CT)
    if (std::isfinite(ct)) ct_lo = std::min(ct_lo, ct), ct_hi = std::max(ct_hi, ct);
  const double ct_ref = r.solution ? r.solution->cost.total : ct_lo;
  const double ct_top = std::min(ct_hi, 2.0 * ct_ref);
  const auto shade = [&](double ct) { return ct_top > ct_ref ? std::log(ct / ct_ref) / std::log(ct_top / ct_ref) : 0.0; };

  const std::string sub =
      r.solution ? "optimum vc = " + fmt(r.solution->vc, 6) + " m/min, f = " + fmt(r.solution->f, 5) +
                       " mm/rev, Vf = " + fmt(r.solution->Vf, 5) +
                       " mm/min, CT = " + fmt(r.solution->cost.total, 6) + " CU; active: " +
                       [&] {
                         std::string a;
                         for (const auto& n : r.active) a += (a.empty() ? "" : ", ") + n;
                         return a.empty() ? std::string("none (bounds only)") : a;
                       }()
                 : std::string("status: ") + to_string(r.status);
  s += "<text x=\"" + fmt_fixed(kLeft, 0) + "\" y=\"50\" font-size=\"12\" fill=\"#333\">" + esc(sub) +
       "</text>\n";

  // Heat map: each block of grid cells is a parallelogram in (ln vc, ln Vf).
  s += "<clipPath id=\"plot\"><rect x=\"" + fmt_fixed(kLeft, 2) + "\" y=\"" + fmt_fixed(kTop, 2) +
       "\" width=\"" + fmt_fixed(kPlotW, 2) + "\" height=\"" + fmt_fixed(kPlotH, 2) + "\"/></clipPath>\n";
  s += "<rect x=\"" + fmt_fixed(kLeft, 2) + "\" y=\"" + fmt_fixed(kTop, 2) + "\" width=\"" +
       fmt_fixed(kPlotW, 2) + "\" height=\"" + fmt_fixed(kPlotH, 2) +
       "\" fill=\"#f4f4f4\" stroke=\"none\"/>\n";
  s += "<g clip-path=\"url(#plot)\" stroke-width=\"0.6\">\n";
  const int sx = std::max(1, (nx - 1 + kMaxCells - 1) / kMaxCells),
            sy = std::max(1, (ny - 1 + kMaxCells - 1) / kMaxCells);
  for (int j0 = 0; j0 + 1 < ny; j0 += sy) {
    const int j1 = std::min(j0 + sy, ny - 1);
    for (int i0 = 0; i0 + 1 < nx; i0 += sx) {
      const int i1 = std::min(i0 + sx, nx - 1);
      const auto c = [&](int i, int j) { return g.CT[static_cast<std::size_t>(j) * nx + i]; };
      const auto okc = [&](int i, int j) { return g.feasible[static_cast<std::size_t>(j) * nx + i] != 0; };
      const double ct = 0.25 * (c(i0, j0) + c(i1, j0) + c(i1, j1) + c(i0, j1));
      const bool ok = okc((i0 + i1) / 2, (j0 + j1) / 2);
      const Rgb col = ok ? ramp(shade(ct)) : pale(ramp(shade(ct)));
      const std::string cs = css(col);
      s += "<polygon points=\"" + xy(ax.x(g.vc[i0]), ax.y(vf(g.vc[i0], g.f[j0]))) + " " +
           xy(ax.x(g.vc[i1]), ax.y(vf(g.vc[i1], g.f[j0]))) + " " +
           xy(ax.x(g.vc[i1]), ax.y(vf(g.vc[i1], g.f[j1]))) + " " +
           xy(ax.x(g.vc[i0]), ax.y(vf(g.vc[i0], g.f[j1]))) + "\" fill=\"" + cs + "\" stroke=\"" + cs +
           "\"/>\n";
    }
  }
  // Feasible-region boundary: the 0.5 iso-line of the feasibility indicator.
  std::vector<double> ind(g.feasible.size());
  for (std::size_t k = 0; k < ind.size(); ++k) ind[k] = g.feasible[k] ? 1.0 : 0.0;
  const auto polyline = [&](const std::vector<std::array<double, 2>>& pts, const std::string& style) {
    std::string l = "<polyline fill=\"none\" " + style + " points=\"";
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (k) l += ' ';
      l += xy(pts[k][0], pts[k][1]);
    }
    return l + "\"/>\n";
  };
  for (const IsoLine& line : iso_lines(ind, nx, ny, 0.5)) {
    std::vector<std::array<double, 2>> pts;
    for (const auto& q : line.pts) {
      const double vc = at_index(g.vc, q[0]), f = at_index(g.f, q[1]);
      pts.push_back({ax.x(vc), ax.y(vf(vc, f))});
    }
    s += polyline(pts, "stroke=\"#111\" stroke-width=\"2.2\"");
  }
  // Near-optimal contours.
  const char* dash[] = {"", "stroke-dasharray=\"7 4\"", "stroke-dasharray=\"2 3\""};
  std::vector<double> deltas;
  for (const ContourLine& c : r.near_optimal) {
    auto it = std::find(deltas.begin(), deltas.end(), c.delta);
    if (it == deltas.end()) {
      deltas.push_back(c.delta);
      it = deltas.end() - 1;
    }
    const std::size_t k = static_cast<std::size_t>(it - deltas.begin());
    std::vector<std::array<double, 2>> pts;
    for (const auto& q : c.pts) pts.push_back({ax.x(q[0]), ax.y(q[1])});
    s += polyline(
        pts, "stroke=\"#c0392b\" stroke-width=\"1.4\" " + std::string(dash[std::min<std::size_t>(k, 2)]));
  }
  // Valley vc*(f).
  std::vector<std::array<double, 2>> vpts;
  for (const FeedOptimum& v : r.valley) {
    if (v.feasible) vpts.push_back({ax.x(v.vc), ax.y(vf(v.vc, v.f))});
  }
  if (!vpts.empty()) {
    s += polyline(vpts, "stroke=\"#1f4e9e\" stroke-width=\"2\"");
    for (const auto& q : vpts) {
      s += "<circle cx=\"" + fmt_fixed(q[0], 2) + "\" cy=\"" + fmt_fixed(q[1], 2) +
           "\" r=\"2.6\" fill=\"#1f4e9e\"/>\n";
    }
  }
  s += "</g>\n";
  // Optimum marker and label.
  if (r.solution) {
    const double ox = ax.x(r.solution->vc), oy = ax.y(r.solution->Vf);
    s += "<circle cx=\"" + fmt_fixed(ox, 2) + "\" cy=\"" + fmt_fixed(oy, 2) +
         "\" r=\"6\" fill=\"#e74c3c\" stroke=\"white\" stroke-width=\"2\"/>\n";
    const bool left = ox > kLeft + kPlotW * 0.7;
    s += "<text x=\"" + fmt_fixed(left ? ox - 10 : ox + 10, 2) + "\" y=\"" + fmt_fixed(oy - 10, 2) +
         "\" text-anchor=\"" + (left ? "end" : "start") +
         "\" font-weight=\"bold\" fill=\"#111\" stroke=\"white\" stroke-width=\"3\" "
         "paint-order=\"stroke\">optimum CT* = " +
         fmt(r.solution->cost.total, 6) + "</text>\n";
  }
  // Frame, ticks, labels.
  s += "<rect x=\"" + fmt_fixed(kLeft, 2) + "\" y=\"" + fmt_fixed(kTop, 2) + "\" width=\"" +
       fmt_fixed(kPlotW, 2) + "\" height=\"" + fmt_fixed(kPlotH, 2) + "\" fill=\"none\" stroke=\"#000\"/>\n";
  for (double t : log_ticks(g.vc.front(), g.vc.back())) {
    const double x = ax.x(t);
    s += "<line x1=\"" + fmt_fixed(x, 2) + "\" y1=\"" + fmt_fixed(kTop + kPlotH, 2) + "\" x2=\"" +
         fmt_fixed(x, 2) + "\" y2=\"" + fmt_fixed(kTop + kPlotH + 6, 2) + "\" stroke=\"#000\"/>\n";
    s += "<text x=\"" + fmt_fixed(x, 2) + "\" y=\"" + fmt_fixed(kTop + kPlotH + 21, 2) +
         "\" text-anchor=\"middle\">" + fmt(t, 4) + "</text>\n";
  }
  for (double t : log_ticks(std::exp(ax.ly0), std::exp(ax.ly1))) {
    const double y = ax.y(t);
    s += "<line x1=\"" + fmt_fixed(kLeft - 6, 2) + "\" y1=\"" + fmt_fixed(y, 2) + "\" x2=\"" +
         fmt_fixed(kLeft, 2) + "\" y2=\"" + fmt_fixed(y, 2) + "\" stroke=\"#000\"/>\n";
    s += "<text x=\"" + fmt_fixed(kLeft - 9, 2) + "\" y=\"" + fmt_fixed(y + 4, 2) +
         "\" text-anchor=\"end\">" + fmt(t, 4) + "</text>\n";
  }
  s += "<text x=\"" + fmt_fixed(kLeft + kPlotW / 2, 2) + "\" y=\"" + fmt_fixed(kTop + kPlotH + 45, 2) +
       "\" text-anchor=\"middle\" font-size=\"14\">cutting speed vc [m/min] (log)</text>\n";
  s += "<text transform=\"translate(" + fmt_fixed(kLeft - 62, 2) + "," + fmt_fixed(kTop + kPlotH / 2, 2) +
       ") rotate(-90)\" text-anchor=\"middle\" font-size=\"14\">feed speed Vf = f·n [mm/min] (log)</text>\n";

  // Caption: the grid box, whose upper feed edge is often the roughness limit f_Ra.
  const double f_Ra = feed_for_ra(p.quality.Ra_max, p.tool.r_eps, p.quality.k_Ra);
  const bool top_is_fRa = std::abs(g.f.back() / f_Ra - 1.0) < 1e-12;
  s += "<text x=\"" + fmt_fixed(kLeft, 2) + "\" y=\"" + fmt_fixed(kHeight - 12, 2) +
       "\" font-size=\"11\" fill=\"#444\">" +
       esc("grid " + std::to_string(nx) + " x " + std::to_string(ny) + ": vc in [" + fmt(g.vc.front(), 5) +
           ", " + fmt(g.vc.back(), 5) + "] m/min, f in [" + fmt(g.f.front(), 5) + ", " + fmt(g.f.back(), 5) +
           "] mm/rev" + (top_is_fRa ? " (upper edge f = f_Ra: the roughness limit)" : "")) +
       "</text>\n";

  // Legend: colour bar and line keys.
  const double lx = kLeft + kPlotW + 30, ly = kTop;
  s += "<text x=\"" + fmt_fixed(lx, 2) + "\" y=\"" + fmt_fixed(ly + 4, 2) +
       "\" font-weight=\"bold\">CT [CU/part]</text>\n";
  const double bh = 200;
  for (int k = 0; k < 50; ++k) {
    const double t = k / 49.0;
    s += "<rect x=\"" + fmt_fixed(lx, 2) + "\" y=\"" + fmt_fixed(ly + 14 + t * bh, 2) +
         "\" width=\"22\" height=\"" + fmt_fixed(bh / 49.0 + 0.6, 2) + "\" fill=\"" + css(ramp(t)) + "\"/>\n";
  }
  for (int k = 0; k <= 4; ++k) {
    const double t = k / 4.0;
    const double ct = ct_ref * std::exp(t * std::log(ct_top / ct_ref));
    s += "<text x=\"" + fmt_fixed(lx + 30, 2) + "\" y=\"" + fmt_fixed(ly + 18 + t * bh, 2) + "\">" +
         fmt(ct, 5) + (k == 4 ? "+" : "") + "</text>\n";
  }
  double ky = ly + bh + 50;
  const auto key = [&](const std::string& style, const std::string& label) {
    s += "<line x1=\"" + fmt_fixed(lx, 2) + "\" y1=\"" + fmt_fixed(ky, 2) + "\" x2=\"" +
         fmt_fixed(lx + 28, 2) + "\" y2=\"" + fmt_fixed(ky, 2) + "\" " + style + "/>\n";
    s += "<text x=\"" + fmt_fixed(lx + 36, 2) + "\" y=\"" + fmt_fixed(ky + 4, 2) + "\">" + esc(label) +
         "</text>\n";
    ky += 22;
  };
  key("stroke=\"#111\" stroke-width=\"2.2\"", "feasible-region boundary");
  s += "<rect x=\"" + fmt_fixed(lx, 2) + "\" y=\"" + fmt_fixed(ky - 7, 2) +
       "\" width=\"28\" height=\"14\" fill=\"" + css(pale(ramp(0.5))) + "\"/>\n<text x=\"" +
       fmt_fixed(lx + 36, 2) + "\" y=\"" + fmt_fixed(ky + 4, 2) + "\">infeasible (pale)</text>\n";
  ky += 22;
  key("stroke=\"#1f4e9e\" stroke-width=\"2\"", "valley vc*(f)");
  for (std::size_t k = 0; k < deltas.size(); ++k) {
    key("stroke=\"#c0392b\" stroke-width=\"1.4\" " + std::string(dash[std::min<std::size_t>(k, 2)]),
        "CT = CT*(1 + " + fmt(deltas[k], 3) + ")");
  }
  s += "<circle cx=\"" + fmt_fixed(lx + 14, 2) + "\" cy=\"" + fmt_fixed(ky, 2) +
       "\" r=\"6\" fill=\"#e74c3c\" stroke=\"white\" stroke-width=\"2\"/>\n<text x=\"" +
       fmt_fixed(lx + 36, 2) + "\" y=\"" + fmt_fixed(ky + 4, 2) + "\">optimum</text>\n";
  s += "</svg>\n";
  return s;
}

}  // namespace cutroute::machining
