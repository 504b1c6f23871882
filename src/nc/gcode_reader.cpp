#include <cutroute/nc/gcode_reader.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <cutroute/core/file.hpp>
#include <cutroute/core/number_format.hpp>
#include <cutroute/core/units.hpp>
#include <cutroute/nc/frames.hpp>

#include "nc/block_scanner.hpp"
#include "nc/gcode_codes.hpp"

namespace cutroute::nc {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::size_t kMaxCodesPerBlock = 16;

// One block's words; G codes in tenths (G90.1 -> 901) so that the dotted codes compare exactly.
struct Block {
  std::array<int, kMaxCodesPerBlock> g{};
  std::size_t ng = 0;
  std::array<int, kMaxCodesPerBlock> m{};
  std::size_t nm = 0;
  std::array<bool, 26> has{};
  std::array<double, 26> val{};
  bool frame = false;

  bool has_word(char c) const { return has[static_cast<std::size_t>(c - 'A')]; }
  double word(char c) const { return val[static_cast<std::size_t>(c - 'A')]; }
};

enum class Motion { none, rapid, line, cw, ccw };

struct ArcGeometry {
  double length = 0.0;  // [mm]
  double radius = 0.0;  // [mm]
  double cx = 0.0;      // centre [mm]
  double cy = 0.0;
};

using detail::g_name;
using detail::inert_g;
using detail::kControllerRadiusShortMm;
using detail::known_letter;
using detail::measured_modal_group;
using detail::num;

class Reader {
 public:
  Reader(std::string_view text, const std::string& file, const ReadOptions& opt)
      : text_(text), file_(file), opt_(opt), x_(opt.start_mm.x), y_(opt.start_mm.y) {}

  Result<ProgramStats> run() {
    std::size_t pos = 0;
    while (pos < text_.size()) {
      const auto line = detail::next_line(text_, pos);
      pos = line.next;
      ++line_no_;
      if (ended_) {
        if (is_frame(line.text)) ++frames_after_end_;
        continue;
      }
      if (auto err = read_line(line.text); !err.message.empty()) return err;
    }
    if (!ended_) {
      return make_error("no program end: the program has no M2 or M30 block", file_,
                        static_cast<long>(line_no_ == 0 ? 1 : line_no_));
    }
    st_.lines = end_line_;
    if (st_.pierces == 0 && st_.feed_off_length_mm > 0.0) warn(first_feed_line_, "gcode.never_cut", never_on_message());
    if (frames_after_end_ > 0) {
      warn(end_line_, "gcode.after_end", std::to_string(frames_after_end_) +
                          " block(s) after the program end (M2/M30) are ignored and not counted as frames");
    }
    return std::move(st_);
  }

 private:
  Diagnostic error(std::string msg) const {
    return make_error(std::move(msg), file_, static_cast<long>(line_no_));
  }

  // `code` is the warning's kind for JSON readers (gcode_reader.hpp lists them).
  void warn(std::size_t line, const char* code, std::string msg) {
    if (st_.warnings.size() < opt_.max_warnings) {
      st_.warnings.push_back(make_warning(std::move(msg), file_, static_cast<long>(line)));
      st_.warnings.back().code = code;
    } else {
      ++st_.suppressed_warnings;
    }
  }

  // Returns an empty diagnostic when the line is fine.
  Diagnostic read_line(std::string_view line) {
    if (auto ow = o_word_keyword(line); !ow.empty())
      return error("o-word " + ow + ": LinuxCNC subroutines and control flow are not read; expand them into the program");
    Block b;
    Diagnostic dup;
    const auto scan = detail::scan_block(line, [&](const detail::Word& w) {
      if (w.letter != 'N' && w.letter != 'O') b.frame = true;
      if (w.letter == 'G') {
        const double t = w.value * 10.0;
        const long r = std::lround(t);
        if (std::abs(t - static_cast<double>(r)) > 1e-6 || r < 0 || r > 99999) {
          warn(line_no_, "gcode.unknown_word", "unknown word G" + num(w.value) + " ignored");
          skip_motion_ = true;
          return;
        }
        if (b.ng == kMaxCodesPerBlock) {
          if (dup.message.empty()) dup = error("more than 16 G words in one block");
          return;
        }
        b.g[b.ng++] = static_cast<int>(r);
      } else if (w.letter == 'M') {
        const long r = std::lround(w.value);
        if (std::abs(w.value - static_cast<double>(r)) > 1e-9 || r < 0 || r > 99999) {
          warn(line_no_, "gcode.unknown_word", "unknown word M" + num(w.value) + " ignored");
          return;
        }
        if (b.nm == kMaxCodesPerBlock) {
          if (dup.message.empty()) dup = error("more than 16 M words in one block");
          return;
        }
        b.m[b.nm++] = static_cast<int>(r);
      } else if (w.letter == 'N') {
        // Sequence numbers carry no meaning for lengths or time, but a controller refuses a block
        // whose number is negative or not a whole number (LinuxCNC: "negative line number").
        if (w.value < 0 || w.value != std::floor(w.value))
          warn(line_no_, "gcode.line_number", "line number N" + num(w.value) + " is not a whole number >= 0 (controllers refuse the block)");
      } else {
        const auto i = static_cast<std::size_t>(w.letter - 'A');
        if (b.has[i] && dup.message.empty()) {
          dup = error(std::string("word ") + w.letter + " appears twice in one block (column " +
                      std::to_string(w.column) + ")");
        }
        b.has[i] = true;
        b.val[i] = w.value;
        if (!known_letter(w.letter))
          warn(line_no_, "gcode.unknown_word", std::string("unknown word ") + w.letter + num(w.value) + " ignored");
      }
    });
    if (scan.error != detail::ScanError::none) {
      // A drawing given where a program was meant: say what it is, not which character failed.
      if (line_no_ <= 2 && text_.substr(0, 200).find("SECTION") != std::string_view::npos)
        return error("not a G-code program: it looks like a DXF drawing (group codes, SECTION); cutroute optimize and "
                     "inspect read drawings");
      return scan_error(scan);
    }
    if (!dup.message.empty()) return dup;
    // A program between two '%' lines ends at the second (LinuxCNC needs no M2/M30 then).
    if (scan.tape_mark) {
      if (percent_open_ && !ended_) {
        ended_ = true;
        end_line_ = line_no_;
        beam_on_ = false;
      }
      if (!any_block_) percent_open_ = true;
    }
    if (!any_block_ && !line_is_blank(line)) any_block_ = true;
    if (scan.tape_mark || !b.frame) {
      skip_motion_ = false;
      return {};
    }
    ++st_.frames;
    Diagnostic d = execute(b);
    skip_motion_ = false;
    return d;
  }

  Diagnostic scan_error(const detail::ScanResult& s) const { return error(detail::scan_message(s)); }

  // Executes one block in RS274/NGC order: F, beam M codes, dwell, units, plane, distance
  // modes, motion, then program end.
  Diagnostic execute(const Block& b) {
    bool dwell = false;
    bool end = false;
    bool set_origin = false;  // G92
    warn_same_modal_group(b);
    for (std::size_t k = 0; k < b.ng; ++k) {
      const int g = b.g[k];
      switch (g) {
        case 0:
          motion_ = Motion::rapid;
          break;
        case 10:
          motion_ = Motion::line;
          break;
        case 20:
          motion_ = Motion::cw;
          break;
        case 30:
          motion_ = Motion::ccw;
          break;
        case 40:
          dwell = true;
          break;
        case 180:
        case 190:
          return error(g_name(g) + ": only the XY plane (G17) is supported");
        case 200:
          scale_ = units::kMmPerInch;
          st_.inch = true;
          break;
        case 210:
          scale_ = 1.0;
          break;
        case 900:
          absolute_ = true;
          break;
        case 910:
          absolute_ = false;
          break;
        case 901:
          arc_absolute_ = true;
          break;
        case 911:
          arc_absolute_ = false;
          break;
        case 920:
          set_origin = true;
          break;
        // G92.1 and G92.2 cancel the offset (G92.2 keeps it for G92.3 to restore).
        case 921:
          offset_x_ = offset_y_ = saved_offset_x_ = saved_offset_y_ = 0.0;
          break;
        case 922:
          offset_x_ = offset_y_ = 0.0;
          break;
        case 923:
          offset_x_ = saved_offset_x_;
          offset_y_ = saved_offset_y_;
          break;
        default:
          if (g == 280 || g == 300) {
            warn(line_no_, "gcode.travel_not_counted", g_name(g) + " (return to a home position) is not followed: its travel is not counted");
            skip_motion_ = true;
          } else if (g == 530) {
            warn(line_no_, "gcode.travel_not_counted", "G53 (a move in machine coordinates) is not followed: its travel is not counted");
            skip_motion_ = true;
          } else if (g == 700 || g == 710) {
            warn(line_no_, "gcode.fanuc_units", fanuc_units_message(g));
            skip_motion_ = true;
          } else if (!inert_g(g)) {
            warn(line_no_, "gcode.unknown_word", "unknown word " + g_name(g) + " ignored; the block's axis words are not executed");
            skip_motion_ = true;
          }
      }
    }
    if (b.has_word('F')) {
      const double f = b.word('F');
      if (f < 0.0) return error("negative feed F" + num(f));
      // A feed this small makes a cut last longer than any sum of times can hold.
      if (f > 0.0 && f < 1.0e-3) return error("feed F" + num(f) + " below 0.001 per minute");
      feed_mm_min_ = f * scale_;
      have_feed_word_ = true;
    }
    // S is the laser power where it matters (GRBL laser mode, LinuxCNC's spindle PWM): at S0 the
    // beam, though switched on, does not cut. Only once the program has set a power above 0, though:
    // a torch ignores S, and a post that writes "M3 S0" for one would otherwise quote no cut at all.
    if (b.has_word('S')) {
      power_set_ = power_set_ || b.word('S') > 0.0;
      zero_power_ = power_set_ && b.word('S') == 0.0;
    }
    // The beam switched on and off in one block: RS274 puts both codes in one modal group, and the
    // controller refuses the block (LinuxCNC: two M codes from the same modal group). Read in order.
    {
      bool on = false, off = false;
      for (std::size_t k = 0; k < b.nm; ++k) on = on || opt_.dialect.switches_on(b.m[k]), off = off || opt_.dialect.switches_off(b.m[k]);
      if (on && off) warn(line_no_, "gcode.beam_on_and_off", "the beam is switched on and off in one block: the controller refuses it; read in the order written");
    }
    for (std::size_t k = 0; k < b.nm; ++k) {
      const int m = b.m[k];
      if (opt_.dialect.switches_on(m)) {
        if (!beam_on_) {
          beam_on_ = true;
          ++st_.pierces;
          repierce_ = false;
          new_cut_ = true;
          pierce_dwelled_ = false;
        }
      } else if (opt_.dialect.switches_off(m)) {
        beam_on_ = false;
        repierce_ = false;
      } else if (m == 2 || m == 30) {
        end = true;
      } else if (m == 98 || m == 99) {
        // A quote without what the subprogram cuts would be wrong, not just rough.
        return error(std::string(m == 98 ? "M98 subprogram call" : "M99 subprogram return") +
                     ": subprograms are not followed, so their cutting and travel would be missing from the "
                     "estimate; expand them into the main program");
      } else if (!(m == 0 || m == 1 || m == 3 || m == 4 || m == 5 || m == 6 || m == 7 || m == 8 || m == 9) &&
                 !opt_.dialect.is_inert(m)) {
        // Named once per code: a post-processor's output codes repeat at every contour.
        if (std::find(st_.unknown_m_codes.begin(), st_.unknown_m_codes.end(), m) == st_.unknown_m_codes.end()) {
          st_.unknown_m_codes.push_back(m);
          warn(line_no_, "gcode.unknown_m_code", "unknown word M" + std::to_string(m) + " ignored (and wherever it appears again)");
        }
      }
      if ((m == 3 || m == 4 || m == 7 || m == 8) && !opt_.dialect.switches_on(m) && foreign_on_ < 0) {
        foreign_on_ = m;
        foreign_on_line_ = line_no_;
      }
    }
    // Fanuc-style controls also dwell X seconds; LinuxCNC reads X there as an axis word.
    const bool fanuc = opt_.dialect.dwell_p_unit == DwellUnit::milliseconds;
    const bool dwell_x = dwell && fanuc && !b.has_word('P') && b.has_word('X');
    if (dwell) {
      if (!b.has_word('P') && !dwell_x)
        return error(fanuc ? "G4 dwell without P (milliseconds) or X (seconds)"
                           : "G4 dwell without P (" + opt_.dialect.name +
                                 " reads G4 P in seconds; a Fanuc-style G4 X dwell is read with --dialect fanuc-ms)");
      const double p = dwell_x ? b.word('X') : b.word('P');
      if (p < 0.0) return error(std::string("negative dwell G4 ") + (dwell_x ? "X" : "P") + num(p));
      const double t = dwell_x ? p : fanuc ? p / 1000.0 : p;
      // Seconds as a Fanuc program's milliseconds: one dwell of minutes in a cutting program.
      if (!fanuc && p >= 100.0 && p == std::floor(p) && !warned_long_dwell_) {
        warn(line_no_, "gcode.dwell_unit", "G4 P" + num(p) + " dwells " + num(p) + " s (" + opt_.dialect.name +
                           " reads P in seconds); if the program was written for a Fanuc-style control, which reads "
                           "P in milliseconds, use --dialect fanuc-ms");
        warned_long_dwell_ = true;
      }
      st_.dwell_s += t;
      ++st_.dwells;
      if (beam_on_ && new_cut_) {
        st_.pierce_dwell_s += t;
        if (!pierce_dwelled_) ++st_.pierce_dwells;
        pierce_dwelled_ = true;
      }
    }
    const bool axes = b.has_word('X') || b.has_word('Y') || b.has_word('Z');
    const bool centre = b.has_word('I') || b.has_word('J') || b.has_word('R');
    if (set_origin) {
      // G92 moves nothing, but every later absolute coordinate is measured from the origin it sets:
      // ignored, the move after it (a step-and-repeat's rapid to the next part) had a wrong length.
      if (!axes) return error("G92 without axis words");
      if (b.has_word('X')) offset_x_ = x_ - b.word('X') * scale_;
      if (b.has_word('Y')) offset_y_ = y_ - b.word('Y') * scale_;
      saved_offset_x_ = offset_x_;
      saved_offset_y_ = offset_y_;
    } else if (dwell_x || (dwell && fanuc && axes)) {
      if (!dwell_x) warn(line_no_, "gcode.dwell_axis_words", "axis words in a G4 dwell block are not executed");
    } else if (!skip_motion_ && (axes || (centre && (motion_ == Motion::cw || motion_ == Motion::ccw)))) {
      if (auto d = move(b); !d.message.empty()) return d;
    }
    if (end) {
      beam_on_ = false;
      ended_ = true;
      end_line_ = line_no_;
    }
    return {};
  }

  Diagnostic check_range(const char* what, double v_mm) const {
    if (!(std::abs(v_mm) <= units::kMaxCoordinateMm))
      // All digits: at six, 1000000.0001 read "1e+06 mm is beyond the accepted range of ±1e+06 mm".
      return error(std::string(what) + " " + format_shortest(v_mm) + " mm is beyond the accepted range of ±" +
                   num(units::kMaxCoordinateMm) + " mm");
    return {};
  }

  Diagnostic move(const Block& b) {
    if (motion_ == Motion::none) return error("axis words without a motion mode (G0, G1, G2 or G3)");
    double nx = x_;
    double ny = y_;
    if (b.has_word('X')) nx = absolute_ ? b.word('X') * scale_ + offset_x_ : x_ + b.word('X') * scale_;
    if (b.has_word('Y')) ny = absolute_ ? b.word('Y') * scale_ + offset_y_ : y_ + b.word('Y') * scale_;
    if (auto d = check_range("X", nx); !d.message.empty()) return d;
    if (auto d = check_range("Y", ny); !d.message.empty()) return d;
    double length = 0.0;
    ArcGeometry arc_geom;
    if (motion_ == Motion::rapid || motion_ == Motion::line) {
      length = std::hypot(nx - x_, ny - y_);
      // Arc words on a straight move mean nothing here, and the controller refuses them (LinuxCNC:
      // "I word with no G2 or G3 ... to use it").
      for (const char w : {'I', 'J', 'R'})
        if (b.has_word(w)) {
          warn(line_no_, "gcode.arc_word_on_line", std::string("word ") + w + " on a straight move (G0/G1) ignored: the controller refuses it");
          break;
        }
    } else {
      auto arc = arc_length(b, nx, ny);
      if (!arc.ok()) return arc.error();
      arc_geom = *arc;
      length = arc_geom.length;
      ++st_.arc_moves;
    }
    const std::size_t pierces_before = st_.pierces;
    bool& warned_feed = have_feed_word_ ? warned_zero_feed_ : warned_no_feed_;
    if (motion_ != Motion::rapid && length > 0.0 && !(feed_mm_min_ > 0.0) && !warned_feed) {
      // The estimate stands (it prices cuts at V_on*(n)), but the program would not run as written.
      warn(line_no_, "gcode.no_feed", std::string(have_feed_word_ ? "feed move at F0" : "feed move before any F word") +
                         ": a controller without a default feed refuses it (LinuxCNC: zero feed rate); its time at the "
                         "programmed feed is not counted");
      warned_feed = true;
    }
    if (motion_ == Motion::rapid) {
      if (length > 0.0) {
        st_.rapid_length_mm += length;
        ++st_.rapid_moves;
        // Before the first cut since the beam came on, the pierce counted at the beam-on code is
        // the next cut's (GRBL laser programs: M4 S0 at the top, then G0 to the first cut).
        if (beam_on_ && !new_cut_) {
          if (!warned_beam_on_rapid_)
            warn(line_no_, "gcode.beam_on_rapid",
                 "rapid move (G0) with the beam on: counted as travel; the next cut counts as a new pierce");
          warned_beam_on_rapid_ = true;
          repierce_ = true;
        }
        if (beam_on_) ++st_.beam_on_rapids;
      }
    } else if (beam_on_ && !zero_power_) {
      if (length > 0.0) {
        if (repierce_) {
          ++st_.pierces;
          repierce_ = false;
        }
        st_.cut_length_mm += length;
        ++st_.cut_moves;
        if (feed_mm_min_ > 0.0)
          st_.cut_time_at_feed_s += length / units::mm_per_min_to_m_per_s(feed_mm_min_) / units::kMmPerM;
        else
          st_.cut_length_no_feed_mm += length;
      }
    } else {
      if (beam_on_ && length > 0.0) {
        // As a rapid with the beam on: travel, and the cut after it starts again (GRBL programs
        // travel so between cuts: "G1 X.. S0", then "G1 X.. S1000").
        if (!warned_zero_power_)
          warn(line_no_, "gcode.zero_power",
               "feed move at S0 with the beam on: no power (as in GRBL's laser mode), counted as beam-off travel at "
               "feed, not cutting; the next cut at S above 0 counts as a new pierce");
        warned_zero_power_ = true;
        if (!new_cut_) repierce_ = true;
      }
      if (length > 0.0 && first_feed_line_ == 0) first_feed_line_ = line_no_;
      st_.feed_off_length_mm += length;
      if (feed_mm_min_ > 0.0)
        st_.feed_off_time_s += length / units::mm_per_min_to_m_per_s(feed_mm_min_) / units::kMmPerM;
      else
        st_.feed_off_length_no_feed_mm += length;
    }
    const bool cut = beam_on_ && !zero_power_ && motion_ != Motion::rapid && length > 0.0;
    if (opt_.moves && length > 0.0)
      record(nx, ny, length, arc_geom, cut, cut && (pierces_before != st_.pierces || new_cut_));
    if (cut) new_cut_ = false;
    x_ = nx;
    y_ = ny;
    return {};
  }

  void record(double nx, double ny, double length, const ArcGeometry& arc, bool cut, bool pierce) {
    Move m;
    m.kind = motion_ == Motion::rapid  ? Move::Kind::rapid
             : motion_ == Motion::line ? Move::Kind::line
             : motion_ == Motion::cw   ? Move::Kind::arc_cw
                                       : Move::Kind::arc_ccw;
    m.beam_on = cut;
    m.pierce = cut && pierce;
    m.x0 = x_;
    m.y0 = y_;
    m.x1 = nx;
    m.y1 = ny;
    m.length_mm = length;
    m.feed_mm_min = feed_mm_min_;
    m.line = line_no_;
    if (motion_ == Motion::rapid || motion_ == Motion::line) {
      m.start_dir_rad = m.end_dir_rad = std::atan2(ny - y_, nx - x_);
    } else {
      // The tangent is the radius direction turned by +90° (counter-clockwise) or -90° (clockwise).
      const double turn = motion_ == Motion::ccw ? 0.5 * std::numbers::pi : -0.5 * std::numbers::pi;
      m.radius_mm = arc.radius;
      m.start_dir_rad = std::atan2(y_ - arc.cy, x_ - arc.cx) + turn;
      m.end_dir_rad = std::atan2(ny - arc.cy, nx - arc.cx) + turn;
    }
    opt_.moves->push_back(m);
  }

  double radius_tol_mm() const {
    return scale_ == 1.0 ? opt_.arc_radius_tol_mm : opt_.arc_radius_tol_inch * units::kMmPerInch;
  }

  // The full turns a G2/G3 makes before its end point beyond the first: P - 1 (LinuxCNC's turn
  // count, P1 when absent).
  Result<double> extra_turns(const Block& b) const {
    if (!b.has_word('P')) return 0.0;
    const double p = b.word('P');
    if (p < 1.0 || p != std::floor(p) || p > 1.0e6)
      return error("arc turn count P" + num(p) + " is not a whole number >= 1");
    return p - 1.0;
  }

  // Once per block: the controller refuses it once, however many pairs it holds.
  void warn_same_modal_group(const Block& b) {
    for (std::size_t k = 1; k < b.ng; ++k)
      for (std::size_t j = 0; j < k; ++j) {
        const int group = measured_modal_group(b.g[k]);
        if (group == 0 || group != measured_modal_group(b.g[j])) continue;
        warn(line_no_, "gcode.same_modal_group",
             g_name(b.g[j]) + " and " + g_name(b.g[k]) +
                 " in one block are of one modal group: the controller refuses the block (LinuxCNC: two G codes "
                 "used from same modal group); read with the last, " + g_name(b.g[k]));
        return;
      }
  }

  // G70/G71 select inches/millimetres on older Fanuc-style controls and are lathe cycles on
  // LinuxCNC: which one the program means cannot be told, so its unit is left as it is and said.
  std::string fanuc_units_message(int g) const {
    const bool inch_code = g == 700;
    const bool read_inch = scale_ != 1.0;
    std::string msg = g_name(g) + " not read: on older Fanuc-style controls it selects " +
                      (inch_code ? "inches" : "millimetres") +
                      ", on LinuxCNC it is a lathe cycle (refused without Q); lengths are read in " +
                      (read_inch ? "inches (G20)" : "millimetres (G21, the default)");
    if (inch_code == read_inch)
      msg += ", as that control would";
    else
      msg += inch_code ? ": if the program meant inches, they are 25.4 times too short"
                       : ": if the program meant millimetres, they are 25.4 times too long";
    return msg + "; write " + (inch_code ? "G20" : "G21") + " for " + g_name(g) +
           " to be sure; the block's axis words are not executed";
  }

  std::string never_on_message() const {
    std::string on;
    for (const int m : opt_.dialect.beam_on) on += (on.empty() ? "M" : ", M") + std::to_string(m);
    std::string msg = "no cutting: the beam is never switched on (dialect " + opt_.dialect.name + " switches it on with " +
                      on + "), yet the program makes " + num(st_.feed_off_length_mm) +
                      " mm of feed moves, read as beam-off travel";
    if (foreign_on_ >= 0) {
      msg += "; it uses M" + std::to_string(foreign_on_) + " (line " + std::to_string(foreign_on_line_) + ")";
      for (const auto& name : builtin_dialect_names())
        if (auto d = builtin_dialect(name); d.ok() && d->switches_on(foreign_on_)) {
          msg += ", which --dialect " + name + " reads as beam on";
          break;
        }
    }
    return msg + ": check --dialect or the machine profile's dialect";
  }

  // "sub" in "o100 sub": the keyword of a LinuxCNC o-word, empty when the line has none.
  static std::string o_word_keyword(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && detail::is_blank(line[i])) ++i;
    if (i < line.size() && line[i] == '/') ++i;
    while (i < line.size() && detail::is_blank(line[i])) ++i;
    if (i >= line.size() || detail::upper(line[i]) != 'O') return {};
    std::size_t j = i + 1;
    if (j < line.size() && line[j] == '<') return "o<...>";  // named o-word
    while (j < line.size() && detail::is_digit(line[j])) ++j;
    if (j == i + 1) return {};
    while (j < line.size() && detail::is_blank(line[j])) ++j;
    std::string word;
    while (j < line.size() && detail::is_alpha(line[j])) word += static_cast<char>(std::tolower(static_cast<unsigned char>(line[j++])));
    static constexpr std::string_view kKeywords[] = {"sub", "endsub", "call", "return", "if", "elseif", "else", "endif",
                                                    "while", "endwhile", "do", "repeat", "endrepeat", "break", "continue"};
    for (const auto k : kKeywords)
      if (word == k) return std::string(line.substr(i, j - i));
    return {};
  }

  static bool line_is_blank(std::string_view line) {
    for (const char c : line)
      if (!detail::is_blank(c)) return false;
    return true;
  }

  // Exact XY length of a G2/G3 move from (x_, y_) to (nx, ny).
  Result<ArcGeometry> arc_length(const Block& b, double nx, double ny) {
    const bool cw = motion_ == Motion::cw;
    const double chord = std::hypot(nx - x_, ny - y_);
    const bool has_ij = b.has_word('I') || b.has_word('J');
    if (b.has_word('R')) {
      if (has_ij) return error("arc with both R and I/J");
      const double r = b.word('R') * scale_;
      const double ar = std::abs(r);
      if (chord <= tol::kSamePointMm)
        return error("R-form arc whose end equals its start (a full circle needs I/J)");
      if (ar <= tol::kSamePointMm) return error("arc radius R" + num(b.word('R')) + " is zero");
      if (ar < chord / 2.0 - radius_tol_mm()) {
        return error("arc radius R" + num(b.word('R')) + " is shorter than half the chord (" +
                     num(chord / 2.0) + " mm)");
      }
      if (chord / 2.0 - ar > kControllerRadiusShortMm)
        warn(line_no_, "gcode.arc_radius_short",
             "arc radius R" + num(b.word('R')) + " is " + num(chord / 2.0 - ar) + " mm short of half the chord (" +
                 num(chord / 2.0) + " mm): the controller refuses it (LinuxCNC: arc radius too small to reach end "
                 "point, beyond " + num(kControllerRadiusShortMm) + " mm); read as the half circle");
      const double half = std::asin(std::min(1.0, chord / (2.0 * ar)));
      const auto extra = extra_turns(b);
      if (!extra.ok()) return extra.error();
      const double sweep = (r >= 0.0 ? 2.0 * half : kTwoPi - 2.0 * half) + *extra * kTwoPi;
      const double radius = std::max(ar, chord / 2.0);
      // Centre: left of the chord for a counter-clockwise arc shorter than 180°, mirrored for
      // clockwise, and again for R < 0.
      const double h = std::sqrt(std::max(0.0, radius * radius - chord * chord / 4.0));
      const double side = (cw ? -1.0 : 1.0) * (r >= 0.0 ? 1.0 : -1.0);
      const double ux = (nx - x_) / chord;
      const double uy = (ny - y_) / chord;
      return ArcGeometry{radius * sweep, radius, 0.5 * (x_ + nx) - side * h * uy,
                         0.5 * (y_ + ny) + side * h * ux};
    }
    if (!has_ij) return error("arc (G2/G3) without I/J or R");
    double cx = 0.0;
    double cy = 0.0;
    if (arc_absolute_) {
      if (!(b.has_word('I') && b.has_word('J'))) return error("arc centre under G90.1 needs both I and J");
      cx = b.word('I') * scale_ + offset_x_;
      cy = b.word('J') * scale_ + offset_y_;
    } else {
      cx = x_ + (b.has_word('I') ? b.word('I') * scale_ : 0.0);
      cy = y_ + (b.has_word('J') ? b.word('J') * scale_ : 0.0);
    }
    if (auto d = check_range("arc centre", std::max(std::abs(cx), std::abs(cy))); !d.message.empty())
      return d;
    const double r0 = std::hypot(x_ - cx, y_ - cy);
    const double r1 = std::hypot(nx - cx, ny - cy);
    if (r0 <= tol::kSamePointMm) return error("arc centre equals its start point (zero radius)");
    // The end must lie on the circle as the controller checks it: LinuxCNC refuses what fails
    // both its absolute and its relative tolerance, and runs the rest as a spiral (the mean
    // radius below). Off by more than the reader's own tolerance but run: said, since a
    // stricter controller may stop there.
    const double off = std::abs(r0 - r1);
    const double abs_limit_mm =
        scale_ == 1.0 ? detail::kControllerArcRadiusAbsMm : detail::kControllerArcRadiusAbsInch * units::kMmPerInch;
    if (off > abs_limit_mm && off > detail::kControllerArcRadiusRel * r0) {
      return error("arc end is not on its circle: start radius " + num(r0) + " mm, end radius " + num(r1) +
                   " mm, the controller refuses it (LinuxCNC: radius to end of arc differs from radius to "
                   "start, beyond " + num(abs_limit_mm) + " mm and 0.1 % of the radius)");
    }
    if (off > radius_tol_mm())
      warn(line_no_, "gcode.arc_off_circle",
           "arc end is " + num(off) + " mm off its circle (start radius " + num(r0) + " mm, end radius " + num(r1) +
               " mm): LinuxCNC runs it as a spiral, a controller with a tighter tolerance may refuse it");
    double sweep = 0.0;
    if (chord <= tol::kSamePointMm) {
      sweep = kTwoPi;  // I/J arc ending where it starts: a full circle
    } else {
      const double a0 = std::atan2(y_ - cy, x_ - cx);
      const double a1 = std::atan2(ny - cy, nx - cx);
      sweep = cw ? a0 - a1 : a1 - a0;
      sweep = std::fmod(sweep, kTwoPi);
      if (sweep < 0.0) sweep += kTwoPi;
    }
    const auto extra = extra_turns(b);
    if (!extra.ok()) return extra.error();
    sweep += *extra * kTwoPi;
    return ArcGeometry{0.5 * (r0 + r1) * sweep, 0.5 * (r0 + r1), cx, cy};
  }

  std::string_view text_;
  const std::string& file_;
  const ReadOptions& opt_;
  ProgramStats st_;
  std::size_t line_no_ = 0;
  std::size_t end_line_ = 0;
  std::size_t frames_after_end_ = 0;
  bool ended_ = false;
  Motion motion_ = Motion::none;
  double scale_ = 1.0;         // mm per program unit
  bool absolute_ = true;       // G90
  bool arc_absolute_ = false;  // G90.1
  bool beam_on_ = false;
  bool warned_beam_on_rapid_ = false;
  bool zero_power_ = false;   // the last S word was S0 (after a power above 0): the beam does not cut
  bool power_set_ = false;    // an S word above 0 was read: S is the beam's power
  bool warned_zero_power_ = false;
  bool repierce_ = false;     // a rapid or an S0 move was made with the beam on: the next cut pierces again
  bool have_feed_word_ = false, warned_zero_feed_ = false, warned_no_feed_ = false, warned_long_dwell_ = false;
  bool percent_open_ = false;    // the program opened with a '%' line: the next one ends it
  bool any_block_ = false;       // a non-blank line was read
  std::size_t first_feed_line_ = 0;  // the first feed move made with the beam off
  int foreign_on_ = -1;          // the first of M3/M4/M7/M8 that this dialect does not read as beam on
  std::size_t foreign_on_line_ = 0;
  bool skip_motion_ = false;  // the current block holds an unknown G code
  bool pierce_dwelled_ = false;  // a dwell was counted for the current pierce
  bool new_cut_ = false;      // a beam-on code was executed: the next recorded cut starts from a pierce
  double feed_mm_min_ = 0.0;  // 0 = not programmed yet
  double x_ = 0.0;            // [mm] current position; programs start at ReadOptions::start_mm
  double y_ = 0.0;            // [mm]
  // G92: where the program's origin lies in the coordinates above [mm]; the saved pair is G92.3's.
  double offset_x_ = 0.0, offset_y_ = 0.0, saved_offset_x_ = 0.0, saved_offset_y_ = 0.0;
};

}  // namespace

Result<ProgramStats> read_gcode(std::string_view program, const std::string& file,
                                const ReadOptions& options) {
  return Reader(program, file, options).run();
}

Result<ProgramStats> read_gcode_file(const std::string& path, const ReadOptions& options) {
  auto buf = read_file(path);  // a directory or an unreadable file: an error naming it
  if (!buf) return buf.error();
  // A UTF-8 byte order mark (Windows editors) is no part of the program.
  std::string_view text(*buf);
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return read_gcode(text, path, options);
}

}  // namespace cutroute::nc
