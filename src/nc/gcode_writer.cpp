#include <cutroute/nc/gcode_writer.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <cutroute/core/number_format.hpp>
#include <cutroute/core/tolerances.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/geometry/arc.hpp>

namespace cutroute::nc {
namespace {

using geometry::Vec2;


// Arc centre from end points and bulge: the chord's perpendicular bisector, offset by
// (1 - b²) / (4 b) chord lengths to the left of the chord direction.
Vec2 arc_center(Vec2 a, Vec2 b, double bulge) {
  const Vec2 d = b - a;
  return (a + b) / 2 + geometry::perp(d) * ((1 - bulge * bulge) / (4 * bulge));
}

}  // namespace

WrittenArc written_arc(Vec2 from, Vec2 to, double bulge, const PostDialect& d) {
  const ProgramGrid grid(d);
  const double res_mm = grid.res_mm;
  const double arc_tol_mm = d.units == "in" ? tol::kGcodeArcRadiusInch * units::kMmPerInch : tol::kGcodeArcRadiusMm;
  WrittenArc w;
  Vec2 c = arc_center(from, to, bulge);
  if (d.arc_format == ArcFormat::r) {
    // The controller puts the centre on the chord's bisector at the written radius.
    w.radius = grid(geometry::distance(c, from));
    const Vec2 dd = to - from;
    const double chord = geometry::norm(dd);
    const double h = std::sqrt(std::max(0.0, w.radius * w.radius - chord * chord / 4));
    w.centre = (from + to) / 2 + geometry::perp(dd) / chord * (bulge > 0 ? h : -h);
    return w;
  }
  const Vec2 exact = c;
  c = from + grid(c - from);
  // On a coarse grid (2 decimals: 0.01 mm, or 0.001 in) the rounded centre can lie 0.014 mm nearer one end
  // than the other, an arc a strict controller refuses (our reader warns beyond 0.01 mm): the grid
  // point next to it with the least difference is taken instead. At the default 1 µm the
  // difference stays below a third of the tolerance, and the centre as rounded is kept.
  auto mismatch = [&](Vec2 cc) { return std::abs(geometry::distance(cc, from) - geometry::distance(cc, to)); };
  if (mismatch(c) > 0.5 * arc_tol_mm) {
    const Vec2 rounded = c;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) {
        const Vec2 cand = from + grid(rounded - from + Vec2{i * res_mm, j * res_mm});
        const double m = mismatch(cand), mc = mismatch(c);
        if (m < mc - 1e-12 || (std::abs(m - mc) <= 1e-12 && geometry::distance(cand, exact) < geometry::distance(c, exact))) c = cand;
      }
    // A grid coarser still (1 decimal) has no such point: the arc goes as chords whose
    // sagitta stays within the grid step.
    if (mismatch(c) > 0.9 * arc_tol_mm) {
      const double r = geometry::distance(exact, from);
      const double step = 2 * std::acos(std::clamp(1 - res_mm / std::max(r, res_mm), -1.0, 1.0));
      w.chords = std::clamp(static_cast<int>(std::ceil(std::abs(4 * std::atan(bulge)) / std::max(step, 1e-3))), 2, 720);
    }
  }
  w.centre = c;
  w.radius = geometry::distance(c, from);
  return w;
}

namespace {

class Emitter {
 public:
  Emitter(const PostDialect& d, WrittenProgram& out)
      : d_(d), out_(out), grid_(d), scale_(grid_.scale) {}

  void start_numbers() { next_n_ = d_.line_number_start; }
  void set_position(Vec2 p) {
    pos_ = quantise(p);
    have_pos_ = true;
  }

  void block(const std::string& text) {
    if (text.empty()) return;
    if (d_.line_numbers) {
      out_.text += 'N';
      out_.text += std::to_string(next_n_);
      out_.text += ' ';
      next_n_ += d_.line_number_step;
    }
    out_.text += text;
    out_.text += '\n';
  }

  void comment(const std::string& text) {
    if (d_.comments == CommentStyle::none) return;
    // ASCII only: many controllers alarm on any other byte in a program (ISO/EIA tape code), and a
    // file name may bring accents. Each non-ASCII character becomes one '?', control codes and
    // parentheses (which would end or nest the comment) a space.
    std::string clean;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const auto c = static_cast<unsigned char>(text[i]);
      if (c >= 0x80) {
        clean += '?';
        if (c >= 0xC0)
          while (i + 1 < text.size() && (static_cast<unsigned char>(text[i + 1]) & 0xC0) == 0x80) ++i;
      } else {
        clean += (c < 0x20 || c == 0x7F || c == '(' || c == ')') ? ' ' : static_cast<char>(c);
      }
    }
    // LinuxCNC refuses a line of more than 255 characters ("Command too long"): a title naming a
    // long file path is cut short.
    constexpr std::size_t kMaxComment = 200;
    if (clean.size() > kMaxComment) clean = clean.substr(0, kMaxComment - 3) + "...";
    if (d_.comments == CommentStyle::paren) {
      out_.text += "(" + clean + ")\n";
    } else {
      out_.text += "; " + clean + "\n";
    }
  }

  void codes(const std::vector<std::string>& lines, double pierce_s, double feed) {
    for (const std::string& line : lines)
      block(fill_placeholders(line, format_fixed(pierce_s, 3), format_fixed(feed * scale_, d_.feed_decimals),
                              format_fixed(std::round(pierce_s * 1000), 0)));
  }

  // Rounds a point to the output resolution (in mm).
  Vec2 quantise(Vec2 p) const { return grid_(p); }

  void rapid(Vec2 to) {
    const Vec2 q = quantise(to);
    if (have_pos_ && q == pos_) return;
    std::string s = "G0 X";
    coord(s, q.x);
    s += " Y";
    coord(s, q.y);
    block(s);
    if (have_pos_) out_.rapid_length_mm += geometry::distance(pos_, q);
    pos_ = q;
    have_pos_ = true;
  }

  // Returns whether a block was written (moves that round to nothing are dropped).
  bool line(Vec2 to, const std::string& feed_word) {
    const Vec2 q = quantise(to);
    if (q == pos_) return false;
    std::string s = "G1 X";
    coord(s, q.x);
    s += " Y";
    coord(s, q.y);
    s += feed_word;
    block(s);
    out_.cut_length_mm += geometry::distance(pos_, q);
    pos_ = q;
    return true;
  }

  // An arc of radius beyond kMaxArcRadiusMm (or below kMinArcRadiusMm) as k chords (plan_arc). Nearly
  // straight arcs (bulge 1e-8 on a 10-mm edge: I J of 2.5e9 mm) made centres that the controller's
  // range, and our own reader, refuse. The chord ends
  // come from the chord-based arc_point_at_sweep, which stays exact where the centre is far away.
  bool flat_arc(Vec2 q, double bulge, int k, const std::string& feed_word) {
    const Vec2 a = pos_;
    const double sweep = 4 * std::atan(bulge);
    bool wrote = false;
    for (int i = 1; i < k; ++i)
      wrote = line(geometry::arc_point_at_sweep(a, q, bulge, sweep * i / k), wrote ? std::string() : feed_word) || wrote;
    return line(q, wrote ? std::string() : feed_word) || wrote;
  }

  bool arc(Vec2 to, double bulge, const std::string& feed_word) {
    const Vec2 q = quantise(to);
    if (q == pos_) return false;
    const ArcPlan plan = plan_arc(geometry::distance(pos_, q), bulge, grid_.res_mm);
    if (plan.form == ArcPlan::Form::line) return line(to, feed_word);
    if (plan.form == ArcPlan::Form::chords) return flat_arc(q, bulge, plan.chords, feed_word);
    const double sweep = 4 * std::atan(bulge);
    if (d_.arc_format == ArcFormat::r && std::abs(sweep) > 150.0 * std::numbers::pi / 180.0) {
      // Split at the arc's midpoint into two arcs of half the sweep.
      const Vec2 c = arc_center(pos_, q, bulge);
      const double a0 = std::atan2(pos_.y - c.y, pos_.x - c.x);
      const double r = geometry::distance(c, pos_);
      const Vec2 mid{c.x + r * std::cos(a0 + sweep / 2), c.y + r * std::sin(a0 + sweep / 2)};
      const double half = std::tan(sweep / 8);
      const bool first = arc(mid, half, feed_word);
      return arc(to, half, first ? std::string() : feed_word) || first;
    }
    // The centre as written: what the controller will cut.
    const WrittenArc w = written_arc(pos_, q, bulge, d_);
    if (w.chords > 0) return flat_arc(q, bulge, w.chords, feed_word);
    const Vec2 c = w.centre;
    std::string s = bulge < 0 ? "G2 X" : "G3 X";
    coord(s, q.x);
    s += " Y";
    coord(s, q.y);
    if (d_.arc_format == ArcFormat::ij) {
      s += " I";
      coord(s, c.x - pos_.x);
      s += " J";
      coord(s, c.y - pos_.y);
    } else {
      s += " R";
      coord(s, w.radius);
    }
    s += feed_word;
    block(s);
    out_.cut_length_mm += written_arc_length(c, q, bulge > 0);
    pos_ = q;
    return true;
  }

  // Length of the arc from the current position to q around centre c, as the controller runs it
  // (mean of the start and end radii, sweep from the two angles).
  double written_arc_length(Vec2 c, Vec2 q, bool ccw) const {
    const double r0 = geometry::distance(c, pos_), r1 = geometry::distance(c, q);
    double sweep = std::atan2(q.y - c.y, q.x - c.x) - std::atan2(pos_.y - c.y, pos_.x - c.x);
    const double two_pi = 2 * std::numbers::pi;
    if (ccw) {
      while (sweep <= 0) sweep += two_pi;
    } else {
      while (sweep >= 0) sweep -= two_pi;
    }
    return std::abs(sweep) * (r0 + r1) / 2;
  }

  std::string feed_word(double feed_mm_min) const {
    std::string s = " F";
    append_fixed(s, feed_mm_min * scale_, d_.feed_decimals);
    return s;
  }

 private:
  void coord(std::string& s, double mm) const { append_fixed(s, mm * scale_, d_.decimals); }

  const PostDialect& d_;
  WrittenProgram& out_;
  ProgramGrid grid_;
  double scale_;
  long long next_n_ = 0;  // a long program from a high start can pass 2^31
  Vec2 pos_{};
  bool have_pos_ = false;
};

}  // namespace

const char* to_string(PieceRole r) {
  switch (r) {
    case PieceRole::lead_in: return "lead_in";
    case PieceRole::contour: return "contour";
    case PieceRole::bridge: return "bridge";
    case PieceRole::lead_out: return "lead_out";
  }
  return "contour";
}

Vec2 tool_off_point(const CutSegment& s) {
  for (auto it = s.pieces.rbegin(); it != s.pieces.rend(); ++it) {
    if (!it->path.vertices.empty()) return it->path.vertices.back().p;
  }
  return s.pierce;
}

bool compensation_held(const CutSegment& from, const CutSegment& to, bool beam_switches) {
  return beam_switches && from.kerf != KerfSide::none && to.after_tab && to.kerf == from.kerf;
}

WrittenProgram write_gcode(const Toolpath& path, const PostDialect& d, const GcodeWriteOptions& options) {
  WrittenProgram out;
  Emitter e(d, out);
  e.start_numbers();
  if (!options.title.empty()) e.comment(options.title);
  e.block(d.units == "in" ? "G20" : "G21");
  // Header (and footer) lines may name {feed} and {pierce_s} too: the job's cutting feed (the first
  // segment's) and pierce time; written literally, "F{feed}" was a block no controller reads.
  const double job_feed = path.segments.empty() ? 0.0 : path.segments.front().feed_mm_min;
  e.codes(d.header, path.pierce_time_s, job_feed);
  e.set_position(path.start);

  // Micro-joints under controller compensation: a segment that resumes its contour past a tab keeps
  // the compensation of the one before (no G40 .. G41 around the gap). Switched on again on the
  // contour itself, the controller would take the resumed cut's first move as its entry move, from
  // the drawn contour to the offset path: half a kerf into the part at the start of that move.
  const bool hold_over_tabs = beam_switches_under_compensation(d);
  bool held = false;  // compensation kept on from the previous segment
  for (std::size_t k = 0; k < path.segments.size(); ++k) {
    const auto& seg = path.segments[k];
    if (options.comments && !seg.label.empty()) e.comment(seg.label);
    for (const Vec2 via : seg.rapid_via) e.rapid(via);  // shop rules: detour around freed parts; tab gap
    e.rapid(seg.pierce);
    e.codes(d.beam_on, path.pierce_time_s, seg.feed_mm_min);
    e.codes(d.pierce, path.pierce_time_s, seg.feed_mm_min);
    ++out.pierces;
    const bool comp = seg.kerf != KerfSide::none;
    if (comp && !held) e.codes(d.thc_on, path.pierce_time_s, seg.feed_mm_min);  // no outputs under G41/G42
    if (comp && !held) e.block(seg.kerf == KerfSide::left ? d.kerf_left : d.kerf_right);
    const bool hold = k + 1 < path.segments.size() && compensation_held(seg, path.segments[k + 1], hold_over_tabs);
    std::string feed = e.feed_word(seg.feed_mm_min);
    bool thc = comp;
    for (const auto& piece : seg.pieces) {
      const bool is_lead = piece.role == PieceRole::lead_in || piece.role == PieceRole::lead_out;
      if (!comp && !is_lead && !thc) {
        e.codes(d.thc_on, path.pierce_time_s, seg.feed_mm_min);
        thc = true;
      } else if (!comp && piece.role == PieceRole::lead_out && thc) {
        e.codes(d.thc_off, path.pierce_time_s, seg.feed_mm_min);
        thc = false;
      }
      const auto& v = piece.path.vertices;
      for (std::size_t i = 0; i + 1 < v.size(); ++i) {
        const bool written = std::abs(v[i].bulge) < tol::kStraightBulge ? e.line(v[i + 1].p, feed)
                                                                         : e.arc(v[i + 1].p, v[i].bulge, feed);
        if (written) feed.clear();  // F is modal: written once per segment, on its first cutting move
      }
    }
    if (comp && !hold) e.block(d.kerf_off);
    if (thc && !hold) e.codes(d.thc_off, path.pierce_time_s, seg.feed_mm_min);
    e.codes(d.beam_off, path.pierce_time_s, seg.feed_mm_min);
    held = hold;
  }
  for (const Vec2 via : path.end_via) e.rapid(via);  // shop rules: detour around freed parts
  e.rapid(path.end);
  e.codes(d.footer, path.pierce_time_s, job_feed);
  e.block(d.program_end);
  return out;
}

}  // namespace cutroute::nc
