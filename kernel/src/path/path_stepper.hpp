#pragma once
// The cutter-point rules (cutter_points.hpp) over any path with a monotonic parameter τ
// and machine axes X (radius), C (spindle angle), Z (axial) as functions of τ. Internal to
// the path module: spiral.cpp and profile.cpp supply the path.
//
// A Path provides:
//   double tau_end() const;
//   void at(double tau, AxisState& s);      // may throw InputError (a missed projection)
//   void at(double tau, const RadialLine& line, AxisState& s);
//                                           // the same, given the radial line at C(τ)
//                                           // (C is affine in τ on every path: the
//                                           // spiral's C = τ, the profile's C = 0)
//   void commit(const AxisState& s);        // the accepted point: the next warm start
//   double cap() const;                     // the largest step in τ
//   double deviation(double x_axis, const RadialLine& c, double z, double b,
//                    double hint_r) const;  // distance of the tool at these axes (C's
//                                           // radial line) from the design; hint_r: the
//                                           // contact radius nearby
//   double block_time(const AxisState& a, const AxisState& b) const;
//                                           // the time from block a to b, up to a constant
//                                           // factor (pvt_rule.hpp)
//   bool creased() const;                   // the design has creases (Surface::has_creases)
//   bool prune_samples() const;             // a creased segment's finer samples may be left
//                                           // out where they cannot hold its peak
//                                           // (Pruning: a nose, whose gap is the least over
//                                           // the section's pieces)
//   bool holds_still() const;               // a nose held at a crease may stay still while
//                                           // τ advances, and a block of no length then
//                                           // has no time (a profile: C stays fixed, and
//                                           // its block time is the X-Z chord)
//   double slide(double x_axis, double c, double z, double b, const AxisState& ideal,
//                double* ends = nullptr) const;
//                                           // how far the tool at these axes rises above
//                                           // the path's own nose `ideal` (nose_section.hpp),
//                                           // the larger of its rises at two ends (`ends`)
//   double stand_off() const;               // where the blocks stand off the design (mm):
//                                           // the centre of the tolerance band
//   double axis_offset() const;             // the programmed point's distance from the
//                                           // nose centre along B (0 unless B follows)
//   std::string why_not_smooth(const AxisState& s) const;
//                                           // where no step meets the tolerance from s:
//                                           // what about the design makes it so, if the
//                                           // path knows ("" otherwise)

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "freeturn/core/number_text.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/path/contact_point.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/path/pvt_rule.hpp"

namespace freeturn::detail {

struct AxisState {
  double tau = 0;
  double x_axis = 0, c = 0, z = 0;  // X, C, Z of the programmed point (nose_section.hpp)
  double b = 0;                     // B (rad) when it follows the normal, else 0
  double contact_r = 0;             // the contact's signed radius in the radial plane at C
  double slope = 0;                 // the section's slope dz/dρ at the contact
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  bool held = false;  // the nose is held at a crease (section_envelope.hpp)
  double uncut = 0;   // mm: the material it leaves there
  double crease_rho = 0;  // the crease it is held at (held only)
  // The nose rolls over a ridge (section_envelope.hpp): the touch may stay at the ridge
  // while the axes move, so the contact the path itself placed there (path_r, before the
  // nose's touch) measures how far the state moved.
  bool rolling = false;  // `slope` is then the nose's tangent at the touch
  bool at_ridge = false;  // the touch lies on a ridge (NoseTouch::at_ridge): so is `slope`
  double path_r = 0;
  double spread = 1;  // how far the touches of neighbouring passes spread (NoseTouch::spread)
  double warm = 0;   // the path's warm start for the next point (a projection distance)
  // What Path::touch_clear has said of this state's own touch (block_touch_clear): clear by
  // any margin up to clear_by, not shown clear by any from not_clear_by. Kept for the touch
  // (contact_r at C) it was asked of, so a state placed anew forgets it.
  struct TouchClearMemo {
    double contact_r = std::numeric_limits<double>::quiet_NaN(), c = 0;
    double clear_by = -1, not_clear_by = std::numeric_limits<double>::infinity();
  };
  mutable TouchClearMemo touch_memo;
};

// One segment of the program as the controller runs it: blocks a and b, and in PVT mode
// the blocks on either side, which set the velocities at a and b (null: the program ends
// there, and the velocity is one-sided).
struct Segment {
  const AxisState* before = nullptr;
  const AxisState& a;
  const AxisState& b;
  const AxisState* after = nullptr;
};

// The machine's position a fraction u of the way through a segment.
class SegmentMotion {
 public:
  template <class Path>
  SegmentMotion(const Path& path, const Segment& s, Interpolation mode)
      : a_(s.a), b_(s.b), cubic_(mode == Interpolation::kCubic) {
    if (!cubic_) return;
    const AxisState& before = s.before ? *s.before : s.a;
    const AxisState& after = s.after ? *s.after : s.b;
    h_ = path.block_time(s.a, s.b);
    const double dt_a = path.block_time(before, s.a) + h_, dt_b = h_ + path.block_time(s.b, after);
    va_[0] = pvt::velocity(before.x_axis, s.b.x_axis, dt_a);
    va_[1] = pvt::velocity(before.c, s.b.c, dt_a);
    va_[2] = pvt::velocity(before.z, s.b.z, dt_a);
    va_[3] = pvt::velocity(before.b, s.b.b, dt_a);
    vb_[0] = pvt::velocity(s.a.x_axis, after.x_axis, dt_b);
    vb_[1] = pvt::velocity(s.a.c, after.c, dt_b);
    vb_[2] = pvt::velocity(s.a.z, after.z, dt_b);
    vb_[3] = pvt::velocity(s.a.b, after.b, dt_b);
  }

  void at(double u, double& x, double& c, double& z, double& bb) const {
    if (!cubic_) {
      x = a_.x_axis + u * (b_.x_axis - a_.x_axis);
      c = a_.c + u * (b_.c - a_.c);
      z = a_.z + u * (b_.z - a_.z);
      bb = a_.b + u * (b_.b - a_.b);
      return;
    }
    x = pvt::hermite(a_.x_axis, va_[0], b_.x_axis, vb_[0], h_, u);
    c = pvt::hermite(a_.c, va_[1], b_.c, vb_[1], h_, u);
    z = pvt::hermite(a_.z, va_[2], b_.z, vb_[2], h_, u);
    bb = pvt::hermite(a_.b, va_[3], b_.b, vb_[3], h_, u);
  }

 private:
  const AxisState& a_;
  const AxisState& b_;
  bool cubic_;
  double h_ = 0, va_[4] = {0, 0, 0, 0}, vb_[4] = {0, 0, 0, 0};  // X, C, Z, B
};

// The largest of the deviation over one segment, signed (> 0: above; < 0: below):
// samples (8 intervals; 32 on a surface with creases), then a parabola through the largest
// and its neighbours. Where the parabola mispredicts the value at its own vertex, the
// deviation is not smooth there and a golden-section search of the bracket finds the peak
// instead. On a surface with creases, with `always_search`, the search is always made: the
// peak there can be a tent at a crease between two samples, and a parabola can predict its
// own vertex well while missing the tent's apex (a compound eye showed a segment 3.5 % over
// its samples' estimate, past the 3 % margin).
// Samples of a segment where the design has creases (8 elsewhere).
constexpr int kCreasedIntervals = 32;

// How well a peak is known: the parabola's check settles it to its part in a hundred (a
// thousand on a creased grid) or to this, whichever is larger; no search is made for one
// under it, nor finer samples taken where a peak under it is all they could find
// (largest_deviation, peak_may_lie_in). A deviation is a difference of millimetre-sized
// coordinates: under about 1e-15 mm it is their rounding, where the parabola never agrees
// with its vertex and a golden-section search finds only the rounding's largest value
// (equal-angle blocks on a stretch that turns as a surface of revolution, the compound
// eye's base between its lenslets, at a 0.2 µm pitch: 82 % of the segments, twelve
// more samples each). The overlaps that give it are known only to 1e-13 mm as well
// (section_envelope.cpp, kUnsought).
constexpr double kPeakKnownTo = 1e-13;  // mm

// std::lround(v) for the grids' indices, without the C library's call (8.6 million of them on
// the chord job cut to 2 mm): for v ≥ 0 its integer part plus one where the fraction, exact
// below 2^52, is at least a half (half away from zero, as lround); a negative v asks lround.
inline int nearest_index(double v) {
  if (!(v >= 0 && v < 1e9)) return static_cast<int>(std::lround(v));
  const int whole = static_cast<int>(v);
  return v - whole >= 0.5 ? whole + 1 : whole;
}

// A peak bracketed by samples e[best − 1] ≤ e[best] ≥ e[best + 1] of a function concave
// about it (the samples' slopes s₁ ≥ s₂ ≥ s₃ ≥ s₄ from e[best − 2] to e[best + 2] fall) lies
// under the secant lines either side: on [best − 1, best] under the line through e[best − 2]
// and e[best − 1] and the one through e[best] and e[best + 1], on [best, best + 1] likewise.
// The higher of the two places where such lines meet bounds the peak above: a tent at a
// crease (linear flanks) reaches it exactly, a smooth peak comes within a few tenths of a
// percent of it at 32 intervals. If the largest deviation found (`found`, the deviation at
// that place included) comes within 0.5 % of the bound, the peak is known to that, 0.5 %
// of the 3 % margin the step search keeps, in one evaluation instead of the golden-section
// search's twenty; else (a non-concave peak) false, and the search takes over. The
// search assumes one peak in the bracket as well: the bound asks nothing more of it.
// Only samples inside the segment are used (e[0] and e[intervals] are the blocks' zeros).
// A deviation above the bound shows the function is not concave there: false.
template <class DeviationAt>
bool peak_within_secant_bound(const double* e, int best, int intervals, double found,
                              DeviationAt&& deviation_at) {
  if (best < 3 || best + 3 > intervals) return false;
  const double s1 = e[best - 1] - e[best - 2], s2 = e[best] - e[best - 1];
  const double s3 = e[best + 1] - e[best], s4 = e[best + 2] - e[best + 1];
  if (!(s1 >= s2 && s2 >= s3 && s3 >= s4 && s1 > s3 && s2 > s4)) return false;
  const double u_left = (s2 - s1) / (s1 - s3), u_right = (s3 - s4) / (s2 - s4);  // from best
  const double bound_left = e[best] + s3 * u_left, bound_right = e[best] + s2 * u_right;
  const double u = bound_left >= bound_right ? u_left : u_right;
  const double bound = std::max(bound_left, bound_right);
  const double largest = std::max(deviation_at((best + u) / intervals), found);
  return largest >= (1 - 5e-3) * bound && largest <= (1 + 1e-9) * bound;
}

// The same bound inside the golden-section search, from its four points t₀ < t₁ < t₂ < t₃
// (the bracket's ends and the two inside it) where their slopes s₁ ≥ s₂ ≥ s₃ fall: a
// function concave on [t₀, t₃] lies under the line through t₁ and t₂ outside [t₁, t₂], and
// on [t₁, t₂] under the lines through t₀, t₁ and through t₂, t₃. The largest deviation
// found coming within 0.5 % of the highest of these bounds ends the search, as above (on
// the compound-eye bench jobs 93 to 94 % of the searches end so, after 6 to 7.5 of their
// twenty steps on average: by then the points straddle the peak where its flanks are
// straight). Without falling slopes (a function not concave on the bracket) false, and the
// search goes on.
inline bool peak_within_bracket_bound(const double (&t)[4], const double (&f)[4], double found) {
  const double s1 = (f[1] - f[0]) / (t[1] - t[0]), s2 = (f[2] - f[1]) / (t[2] - t[1]);
  const double s3 = (f[3] - f[2]) / (t[3] - t[2]);
  if (!(s1 >= s2 && s2 >= s3 && s1 > s3)) return false;
  // Outside [t₁, t₂]: the line through t₁ and t₂, highest at t₀ where it falls toward t₂,
  // at t₃ where it rises.
  double bound = s2 < 0 ? f[1] - s2 * (t[1] - t[0]) : f[2] + s2 * (t[3] - t[2]);
  // Inside: the lower of the two outer lines, highest where they cross (within [t₁, t₂]).
  const double cross =
      std::clamp(t[1] + (f[2] - f[1] - s3 * (t[2] - t[1])) / (s1 - s3), t[1], t[2]);
  bound = std::max(bound, std::min(f[1] + s1 * (cross - t[1]), f[2] + s3 * (cross - t[2])));
  return found >= (1 - 5e-3) * bound;
}

// How well a smooth segment's fourths know its peak (peak_of_one_parabola) besides its part
// in a hundred. The blocks' zeros are exact, but the samples between them are overlaps a
// search settled (section_envelope.cpp), and on a compound eye's base at a 2 µm pitch they
// stand a few 1e-13 mm off all along segments whose sag is no larger: such a profile is
// flat, no parabola through the zeros fits it, and two in five of those segments were
// sampled in full for a peak of 0.0005 nm. 1e-12 mm is a hundred-thousandth of the finest
// chord tolerance a job may ask (0.1 nm).
constexpr double kSagKnownTo = 1e-12;  // mm

// A smooth segment's fourths: where the deviation's sizes at 1/4, 1/2 and 3/4 (e[2], e[4],
// e[6] of eight intervals) and the blocks' zeros at both ends lie on one concave parabola
// (the zeros within 1 % of its vertex's height, or kSagKnownTo), and the deviation at that
// vertex is the parabola's there within as much, the peak is known as the eight intervals'
// parabola check knows it (to 1 %), from six values on one parabola instead of three, in
// four evaluations instead of eight. The deviation over a short segment of a smooth design
// is the chord's sag, about 4·d·t(1 − t) with higher-order terms a small part of it; where
// it is not (a turn of sign, two peaks, a feature between the samples) the six values do
// not agree, and the caller samples the eighths. Fourths all under half of kSagKnownTo
// know the peak to that (a sag's fourths are 3/4 of its peak).
template <class DeviationAt>
bool peak_of_one_parabola(const double* e, DeviationAt&& deviation_at) {
  if (std::max({e[2], e[4], e[6]}) <= 0.5 * kSagKnownTo) return true;
  const double second = e[2] - 2 * e[4] + e[6];  // per half of the segment
  const double slope = 0.5 * (e[6] - e[2]);      // per half, at the middle
  // q(u) = e[4] + slope·u + second·u²/2 at u = (j − 4)/2 half-segments from the middle.
  if (!(second < 0)) return false;
  const double u = std::clamp(-slope / second, -1.5, 1.5);
  const double predicted = e[4] + slope * u + 0.5 * second * u * u;
  const double at_start = e[4] - 2 * slope + 2 * second, at_end = e[4] + 2 * slope + 2 * second;
  const double allowed = 1e-2 * predicted + kSagKnownTo;
  if (!(std::abs(at_start) <= allowed && std::abs(at_end) <= allowed)) return false;
  const double at_vertex = deviation_at(0.5 + 0.25 * u);
  return std::abs(at_vertex - predicted) <= allowed;
}

// Whether the largest deviation may lie in (lo, hi) of the grid, both sampled, above
// `best_found`: false only where the samples either side show the deviation concave about
// the interval (the slopes from the nearest sampled neighbours beyond, through lo and hi,
// fall), so that it lies under the secant lines through each side's pair extended across
// it (the bound of peak_within_secant_bound), and that bound stays below what was found.
// At a grid's end only the one side's line bounds it.
//
// Only where those four samples lie above the band's centre (`above`): a nose's distance
// from the design is the least over the section's pieces, so where a crease passes under
// it the distance kinks concave (a tent, which the bound holds), and so does its height
// above the centre. Below the centre the deviation's size is the largest of the pieces'
// overlaps: there it kinks convex, and a piece that overlaps most only between two
// samples would lie above any line through them. So does the contact's own distance
// without a nose, either way, and the caller prunes only with one (Path::prune_samples).
// `above` null: no such condition, for a smooth part of the deviation (Pruning::parts),
// which is bounded where its slopes rise as well: convex about the interval, it is highest
// at one of its ends (a tent could hide between two samples whose slopes rise, but a
// smooth part has none). Nor does a smooth part whose four samples are all within half of
// kPeakKnownTo of 0 rise past kPeakKnownTo between them: there the samples are rounding,
// which shows no shape, and the slopes' test would fail on every such interval (a nose
// riding a lenslet's rim at a 0.2 µm pitch took 20 of the 33 states of its slide so).
inline bool peak_may_lie_in(const double* e, const bool* known, const bool* above, int intervals,
                            int lo, int hi, double best_found) {
  int before = lo - 1, after = hi + 1;
  while (before >= 0 && !known[before]) --before;
  while (after <= intervals && !known[after]) ++after;
  if (above && (!above[lo] || !above[hi] || (before >= 0 && !above[before]) ||
                (after <= intervals && !above[after])))
    return true;
  const bool has_before = before >= 0, has_after = after <= intervals;
  if (!has_before && !has_after) return true;
  if (!above && best_found >= kPeakKnownTo) {
    // A smooth part whose samples about the interval are all rounding, either sign (signed
    // samples all below it but far from 0 could still bracket a peak above it).
    double largest = std::max(std::abs(e[lo]), std::abs(e[hi]));
    if (has_before) largest = std::max(largest, std::abs(e[before]));
    if (has_after) largest = std::max(largest, std::abs(e[after]));
    if (largest <= 0.5 * kPeakKnownTo) return false;
  }
  const double across = (e[hi] - e[lo]) / (hi - lo);
  const double rising = has_before ? (e[lo] - e[before]) / (lo - before) : 0.0;
  const double falling = has_after ? (e[after] - e[hi]) / (after - hi) : 0.0;
  if ((has_before && !(rising >= across)) || (has_after && !(across >= falling))) {
    // A smooth part whose slopes rise instead: convex about the interval, highest at an end.
    const bool convex =
        !above && (!has_before || rising <= across) && (!has_after || across <= falling);
    return !(convex && std::max(e[lo], e[hi]) < best_found);
  }
  double bound;
  if (!has_after) {
    bound = std::max(e[lo], e[lo] + rising * (hi - lo));
  } else if (!has_before) {
    bound = std::max(e[hi], e[hi] - falling * (hi - lo));
  } else if (rising > falling) {
    // The two lines cross where the one through lo's pair meets the one through hi's.
    const double u = std::clamp((e[hi] - e[lo] - falling * hi + rising * lo) / (rising - falling),
                                static_cast<double>(lo), static_cast<double>(hi));
    bound = std::min(e[lo] + rising * (u - lo), e[hi] + falling * (u - hi));
  } else {
    bound = std::max(e[lo], e[hi]);  // all three slopes equal: a line
  }
  return !(bound < best_found);
}

// Pruning::check: whether the caller knows the deviation free of narrow features over the
// k-th eighth, asked only where a sample there would be left out.
class EighthCheck {
 public:
  virtual bool free_throughout(int k) const = 0;

 protected:
  ~EighthCheck() = default;
};

// Where largest_deviation may leave a creased grid's finer samples out: in the eighths of
// the segment marked, where the deviation is known to be free of narrow features a
// coarser sample could miss, and only where peak_may_lie_in says its peak cannot lie,
// above the largest deviation found or `floor` (a peak under which does not change the
// caller's answer). The eight intervals' samples are always taken, and the peak's
// neighbours that the search after them reads.
struct Pruning {
  bool eighth[8] = {true, true, true, true, true, true, true, true};
  // A marked eighth is pruned only where this says so as well, asked once an eighth and
  // only when a sample there would first be left out (it may cost more than the samples
  // it saves); null: every marked eighth.
  const EighthCheck* check = nullptr;
  mutable signed char checked[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // 0 not asked, 1 yes, −1 no
  bool free_throughout(int k) const {
    if (!check) return true;
    if (checked[k] == 0) checked[k] = check->free_throughout(k) ? 1 : -1;
    return checked[k] > 0;
  }
  double floor = 0;
  // Where the deviation is the larger of two parts, each smooth where the eighth is marked
  // (the slide: the rises at the two ends of the stretch a pass cuts), their signed values
  // at the grid's samples, written by the deviation as it samples: each part is bounded on
  // its own, for the larger of two concave functions is not concave (where the other
  // overtakes between two samples it kinks up).
  const double* parts[2] = {nullptr, nullptr};
};
inline constexpr Pruning kPruneEveryEighth{};

// The step search's screen of a trial segment (distribute): where every sample of its eight
// intervals lies within `below` of the band's centre, the segment is not measured further
// (no finer samples, no peak search, no slide) and `coarse_only` is set; the value returned
// is then that of those samples alone, which a peak between them could exceed.
struct CoarseScreen {
  double below = 0;
  bool coarse_only = false;
};

// The largest deviation (described above kCreasedIntervals). Its samples are taken coarse
// to fine (every eighth, then the fourths between, ...). Where a level's largest sample already
// passes `cutoff`, the segment is over it whatever the finer samples show, and the search stops
// there: it returns that level's estimate (its largest sample, raised to the parabola's vertex
// through it and its neighbours when that is higher), which is enough for the step search to
// predict its next step from. A rejected trial then costs 3 to 7 samples instead of 33.
//
// `as_smooth`: the segment is known to stay clear of the design's creases (segment_error),
// and is sampled as on a smooth design. `screen`: CoarseScreen, above.
template <class Path, class Deviation>
double largest_deviation(const Path& path, Deviation&& deviation, bool always_search = false,
                         double cutoff = std::numeric_limits<double>::infinity(),
                         bool as_smooth = false, const Pruning* pruning = nullptr,
                         CoarseScreen* screen = nullptr) {
  constexpr int kMaxIntervals = kCreasedIntervals;
  const bool creased = path.creased() && !as_smooth;
  const int intervals = creased ? kMaxIntervals : 8;
  double signed_worst = 0;
  const auto signed_deviation_at = [&](double t) {
    const double d = deviation(t);
    if (std::abs(d) > std::abs(signed_worst)) signed_worst = d;
    return d;
  };
  const auto deviation_at = [&](double t) { return std::abs(signed_deviation_at(t)); };
  double e[kMaxIntervals + 1];
  bool known[kMaxIntervals + 1] = {}, above[kMaxIntervals + 1] = {};
  e[0] = e[intervals] = 0;  // the blocks themselves lie on the design
  known[0] = known[intervals] = above[0] = above[intervals] = true;
  int best = intervals / 4;
  const auto sample = [&](int j) {
    const double d = signed_deviation_at(static_cast<double>(j) / intervals);
    e[j] = std::abs(d);
    known[j] = true;
    above[j] = d >= 0;
    if (e[j] > e[best]) best = j;
  };
  // Whether the deviation may pass `found` between samples lo and hi (Pruning): true
  // unless their eighth is marked and the bound says it cannot.
  const auto may_pass = [&](int lo, int hi, double found) {
    const int k = 8 * lo / intervals;
    if (!pruning || !pruning->eighth[k] || !known[lo] || !known[hi]) return true;
    const bool bound_passes =
        pruning->parts[0]
            ? peak_may_lie_in(pruning->parts[0], known, nullptr, intervals, lo, hi, found) ||
                  peak_may_lie_in(pruning->parts[1], known, nullptr, intervals, lo, hi, found)
            : peak_may_lie_in(e, known, above, intervals, lo, hi, found);
    return bound_passes || !pruning->free_throughout(k);
  };
  for (int stride = intervals / 4; stride >= 1; stride /= 2) {
    // The first level takes every multiple of its stride; each finer one, the odd ones.
    const int first = stride, step = stride == intervals / 4 ? stride : 2 * stride;
    // Past the eight intervals, in a prunable eighth only where the peak may lie.
    const bool pruned = pruning && 8 * stride < intervals;
    for (int j = first; j < intervals; j += step) {
      // Within the 0.5 % the peak search itself settles for (peak_within_secant_bound), or
      // kPeakKnownTo; an interval left out at a coarser level has no samples at its ends here.
      if (pruned && pruning->eighth[8 * j / intervals] &&
          (!known[j - stride] || !known[j + stride] ||
           !may_pass(j - stride, j + stride,
                     (1 + 5e-3) * std::max({e[best], pruning->floor, kPeakKnownTo}))))
        continue;
      sample(j);
    }
    if (stride > 1 && e[best] > cutoff) {
      if (!known[best - stride] || !known[best + stride])
        return std::copysign(e[best], signed_worst);
      const double left = e[best - stride], right = e[best + stride];
      const double curvature = left - 2 * e[best] + right;
      const double vertex = curvature < 0 ? e[best] - 0.125 * (left - right) * (left - right) / curvature
                                          : e[best];
      const double estimate = std::min(vertex, 2 * e[best]);
      return std::copysign(estimate, signed_worst);
    }
    if (stride == 2 && intervals == 8 && e[best] <= cutoff && peak_of_one_parabola(e, deviation_at))
      return signed_worst;
    if (screen && 8 * stride == intervals && e[best] <= screen->below) {
      screen->coarse_only = true;
      return signed_worst;
    }
  }
  // The finish reads the peak's neighbours two either side; a pruned grid may lack some
  // (and one found higher moves the peak, whose own are then read).
  if (pruning) {
    for (int seen = -1; seen != best;) {
      seen = best;
      for (int j = std::max(1, seen - 2); j <= std::min(intervals - 1, seen + 2); ++j)
        if (!known[j]) sample(j);
    }
    // A peak that cannot pass the floor either side of the largest sample changes nothing
    // for the caller, and is not searched for (the slide's, far under the gap).
    if (pruning->floor > 0 && !may_pass(best - 1, best, pruning->floor) &&
        !may_pass(best, best + 1, pruning->floor))
      return signed_worst;
  }
  const double denominator = e[best - 1] - 2 * e[best] + e[best + 1];
  if (!(denominator < 0)) return signed_worst;
  const double shift = std::clamp(0.5 * (e[best - 1] - e[best + 1]) / denominator, -1.0, 1.0);
  const double predicted = e[best] - 0.25 * (e[best - 1] - e[best + 1]) * shift;
  const double at_vertex = deviation_at((best + shift) / intervals);
  // Every sample and the vertex under kPeakKnownTo: rounding chose the bracket, and no
  // search of it (a creased grid's, always made) can say where a peak lies.
  if (std::max(e[best], at_vertex) <= kPeakKnownTo) return signed_worst;
  if (!(creased && always_search) &&
      std::abs(at_vertex - predicted) <= (creased ? 1e-3 : 1e-2) * predicted + kPeakKnownTo)
    return signed_worst;
  if (peak_within_secant_bound(e, best, intervals, std::abs(signed_worst), deviation_at))
    return signed_worst;
  // Golden-section search for the maximum on [t_{best−1}, t_{best+1}].
  constexpr double kGolden = 0.6180339887498949;
  double lo = (best - 1.0) / intervals, hi = (best + 1.0) / intervals;
  double f_lo = e[best - 1], f_hi = e[best + 1];
  double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
  double f1 = deviation_at(x1), f2 = deviation_at(x2);
  for (int it = 0; it < 20; ++it) {
    if (f1 > f2) {
      hi = x2;
      f_hi = f2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kGolden * (hi - lo);
      f1 = deviation_at(x1);
    } else {
      lo = x1;
      f_lo = f1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kGolden * (hi - lo);
      f2 = deviation_at(x2);
    }
    if (peak_within_bracket_bound({lo, x1, x2, hi}, {f_lo, f1, f2, f_hi}, std::abs(signed_worst)))
      break;
  }
  return signed_worst;
}

// How far apart two touches lie in (x, y): ρ_a along `a`'s radial line, ρ_b along `b`'s.
inline double touches_apart(const RadialLine& a, double rho_a, const RadialLine& b, double rho_b) {
  const double dx = rho_b * b.cos - rho_a * a.cos, dy = rho_b * b.sin - rho_a * a.sin;
  return std::sqrt(dx * dx + dy * dy);  // mm: std::hypot's care for overflow is not needed
}

// Path::touch_clear at a block's own touch (`line`: the radial line at its C), remembered
// on the state: the same block is checked for every trial that starts from it, and
// before that as the end of the trial that placed it, each time by half that step. A
// touch clear by W is clear by any margin less (every touch within the smaller disc lies
// in the larger); where a margin was not shown clear, no larger one is tried and the
// answer is no (the test is monotonic in the margin in what it means, though not to the
// last bit of its arithmetic).
template <class Path>
bool block_touch_clear(const Path& path, const RadialLine& line, const AxisState& s,
                       double margin) {
  AxisState::TouchClearMemo& memo = s.touch_memo;
  if (!(memo.contact_r == s.contact_r && memo.c == s.c)) memo = {s.contact_r, s.c};
  if (margin <= memo.clear_by) return true;
  if (margin >= memo.not_clear_by) return false;
  const bool clear = path.touch_clear(line, s.contact_r, margin);
  (clear ? memo.clear_by : memo.not_clear_by) = margin;
  return clear;
}

// Segments clear of creases (docs/path.md): where the nose touches nowhere near a crease
// throughout, neither the interpolated nose nor the path's can meet one (the envelope of
// touch_clear_of_creases), and the segment is measured as on a smooth design: 8 intervals,
// no crease search, no slide. Known only after the samples, from their touches: those of
// the interpolated nose at the samples on the eighths' grid (the fourths alone where they
// settle the peak, all nine where they do not or where the fourths' certificate fails),
// and the path's own at the blocks and at the middle sample's angle, each clear by a margin
// for what lies between (the largest step between neighbouring sampled touches, and twice
// how far the path's touch there lies from the interpolated one; the path's touches are the
// blocks' at the ends). A segment rejected on these samples
// needs no certificate: a crease the search left out could only raise the section toward
// the nose, which is rejected either way or would have been, at worst, a step too short.
// True when the segment is measured so, its deviation (or a rejection's estimate) in `gap`;
// false, having measured nothing that counts, where it cannot be shown clear.
//
// grid_line: the radial lines at the segment's `grid` + 1 equal steps of C (C at the ends is
// the blocks'); line_at(C): the line at any other angle. Linear motion's samples lie on the
// grid's lines; a cubic's C is not affine in the fraction, and its samples take their own.
template <class Path, class LineAt>
bool measure_clear_of_creases(const Path& path, const SegmentMotion& motion, const AxisState& a,
                              const AxisState& b, const RadialLine* grid_line, int grid,
                              bool linear, LineAt&& line_at, double target, double& gap) {
  const auto point_on = [](const RadialLine& line, double rho) {
    return Eigen::Vector2d(rho * line.cos, rho * line.sin);
  };
  const Eigen::Vector2d ends[2] = {point_on(grid_line[0], a.contact_r),
                                   point_on(grid_line[grid], b.contact_r)};
  // How far from each block's touch every touch is known clear: half the step where both
  // are clear by that (a filter: the touches between lie mostly within it), else none,
  // and each touch is checked below on its own.
  double cover = 0.5 * (ends[1] - ends[0]).norm();
  if (!block_touch_clear(path, grid_line[0], a, cover) ||
      !block_touch_clear(path, grid_line[grid], b, cover)) {
    if (!block_touch_clear(path, grid_line[0], a, 0) ||
        !block_touch_clear(path, grid_line[grid], b, 0))
      return false;
    cover = 0;
  }
  constexpr int kSmooth = 8;
  const int every = grid / kSmooth;
  RadialLine line[kSmooth + 1];
  double touch[kSmooth + 1];
  // Which of the nine were sampled: a segment whose fourths settle its peak
  // (peak_of_one_parabola) leaves the odd eighths out.
  bool sampled[kSmooth + 1] = {};
  std::fill(touch, touch + kSmooth + 1, std::numeric_limits<double>::quiet_NaN());
  line[0] = grid_line[0];
  touch[0] = a.contact_r;
  line[kSmooth] = grid_line[grid];
  touch[kSmooth] = b.contact_r;
  sampled[0] = sampled[kSmooth] = true;
  const auto deviation = [&](double t) {
    double x, c, z, bb, rho;
    motion.at(t, x, c, z, bb);
    const int j = nearest_index(t * grid);
    const bool on_grid = static_cast<double>(j) / grid == t;
    const RadialLine sample_line = linear && on_grid ? grid_line[j] : line_at(c);
    const double hint = a.contact_r + t * (b.contact_r - a.contact_r);
    const double d = path.deviation_near_hint(x, sample_line, z, bb, hint, rho);
    if (on_grid && j % every == 0) {
      line[j / every] = sample_line;
      touch[j / every] = rho;
      sampled[j / every] = true;
    }
    return d - path.stand_off();
  };
  gap = largest_deviation(path, deviation, false, target, true);
  if (std::abs(gap) > target) return true;
  // The path's own state at the middle sample's angle (C is affine in τ on every path).
  if (!sampled[kSmooth / 2] || !std::isfinite(touch[kSmooth / 2])) return false;
  const RadialLine& mid_line = line[kSmooth / 2];
  const double tau_mid = linear || b.c == a.c
                             ? a.tau + 0.5 * (b.tau - a.tau)
                             : a.tau + (mid_line.theta - a.c) / (b.c - a.c) * (b.tau - a.tau);
  AxisState mid;
  path.at(tau_mid, mid_line, mid);
  if (mid.held || !std::isfinite(mid.contact_r)) return false;
  const Eigen::Vector2d middle = point_on(mid_line, touch[kSmooth / 2]);
  // Whether every touch of the segment is clear, from the sampled ones: each clear by a
  // margin for what lies between them (the widest step between neighbouring sampled
  // touches).
  const auto certified = [&] {
    for (int j = 0; j <= kSmooth; ++j)
      if (sampled[j] && !std::isfinite(touch[j])) return false;
    double margin = 2 * (point_on(mid_line, mid.contact_r) - middle).norm();
    double widest = 0;
    for (int j = 1, last = 0; j <= kSmooth; ++j) {
      if (!sampled[j]) continue;
      widest = std::max(widest,
                        (point_on(line[j], touch[j]) - point_on(line[last], touch[last])).norm());
      last = j;
    }
    margin += widest;
    if (!std::isfinite(margin)) return false;
    // One check covers many: a touch clear by W covers every touch within W − margin of it
    // (a crease's distance changes no faster than the point). The blocks' touches were
    // checked by half a step; the others are checked from the middle sample's touch, and
    // one by one only where that fails: the same answer, fewer queries.
    const RadialLine* open_line[kSmooth + 2];
    double open_rho[kSmooth + 2];
    int open_count = 0;
    double reach = 0;  // from the middle sample's touch to the farthest open one
    const auto needs = [&](const RadialLine& on, double rho) {
      const Eigen::Vector2d p = point_on(on, rho);
      if (std::min((p - ends[0]).norm(), (p - ends[1]).norm()) + margin <= cover) return;
      open_line[open_count] = &on;
      open_rho[open_count++] = rho;
      reach = std::max(reach, (p - middle).norm());
    };
    for (int j = 0; j <= kSmooth; ++j)
      if (sampled[j]) needs(line[j], touch[j]);
    needs(mid_line, mid.contact_r);
    if (open_count == 0 || path.touch_clear(mid_line, touch[kSmooth / 2], margin + reach))
      return true;
    for (int k = 0; k < open_count; ++k)
      if (!path.touch_clear(*open_line[k], open_rho[k], margin)) return false;
    return true;
  };
  if (certified()) return true;
  // A segment whose fourths settled its peak has touches only at its fourths, twice as far
  // apart as the eighths', and a margin twice as wide: near a crease its certificate can
  // fail where the eighths' would pass, and a full measure costs many times the four
  // samples that give them. An eighth's sample above the peak the fourths gave shows
  // that peak wrong: the segment is then measured in full.
  bool retried = false;
  for (int j = 1; j < kSmooth; j += 2) {
    if (sampled[j]) continue;
    if (std::abs(deviation(static_cast<double>(j) / kSmooth)) > std::abs(gap)) return false;
    retried = true;
  }
  return retried && certified();
}

// The largest distance of the interpolated motion from the band's centre (the design
// raised by the path's stand-off) over one segment, signed (> 0: above it; < 0: below,
// and below the design itself where it passes the stand-off).
//
// On a creased surface the distance above is also the nose's rise over the path's own
// nose at the same τ (Path::slide): where the path's nose is held at a crease or changes
// flank across one, an interpolated nose that keeps touching the design may still touch it
// far from where the path's does, and the cusp to the next pass grows with the slide.
// Whether a segment passes such a place cannot be told from its ends (a hold can begin and
// end between them), so every segment that meets the gap target is measured again with
// it; one that misses the target is rejected on its gap alone.
//
// `screen` (CoarseScreen): a trial whose gap's coarse samples all lie within screen->below
// of the centre returns their value, without the rest of the gap or the slide.
template <class Path>
double segment_error(const Path& path, const Segment& segment, Interpolation mode, double target,
                     CoarseScreen* screen = nullptr) {
  const SegmentMotion motion(path, segment, mode);
  const AxisState &a = segment.a, &b = segment.b;
  // The grid of the creased design's samples (the slide's search runs on those only).
  constexpr int kGrid = kCreasedIntervals;
  const auto grid_index = [&](double t) {
    const int j = nearest_index(t * kGrid);
    return j >= 0 && j <= kGrid && static_cast<double>(j) / kGrid == t ? j : -1;
  };
  // The radial lines at C(τ) on the grid, by rotation from the segment's start: two sines
  // and cosines a segment instead of one a sample (C is affine in τ, so these are also
  // the lines of linear motion's samples; a cubic's C is not, and takes its own).
  const RadialLine unit((b.c - a.c) / kGrid);
  RadialLine grid_line[kGrid + 1];
  grid_line[0] = RadialLine(a.c);
  for (int j = 1; j <= kGrid; ++j) {
    const double t = static_cast<double>(j) / kGrid;
    const RadialLine& last = grid_line[j - 1];
    grid_line[j].theta = a.c + t * (b.c - a.c);  // as SegmentMotion moves C
    grid_line[j].cos = last.cos * unit.cos - last.sin * unit.sin;
    grid_line[j].sin = last.sin * unit.cos + last.cos * unit.sin;
  }
  const bool linear = mode == Interpolation::kLinear;
  // The line at any other angle (a sample between the grid's, or a cubic's C), by rotation
  // from the grid's nearest line, within half a grid step of it on a linear segment.
  const auto line_at = [&](double angle) {
    const double u = b.c != a.c ? (angle - a.c) / (b.c - a.c) : 0.0;
    const int j = nearest_index(std::clamp(u, 0.0, 1.0) * kGrid);
    return grid_line[j].turned_to(angle);
  };
  const auto gap_at = [&](double t, int j, double& x, double& c, double& z, double& bb) {
    motion.at(t, x, c, z, bb);
    const double hint = a.contact_r + t * (b.contact_r - a.contact_r);
    const double d = linear && j >= 0 ? path.deviation(x, grid_line[j], z, bb, hint)
                                      : path.deviation(x, line_at(c), z, bb, hint);
    return d - path.stand_off();
  };
  // Segments clear of creases: measured as on a smooth design.
  if (path.creased() && !a.held && !b.held) {
    double smooth_gap;
    if (measure_clear_of_creases(path, motion, a, b, grid_line, kGrid, linear, line_at, target,
                                 smooth_gap))
      return smooth_gap;
  }
  // Every peak searched on a creased surface (the peak there can be a tent at a crease).
  const bool prune = path.prune_samples();
  const double gap = largest_deviation(
      path,
      [&](double t) {
        double x, c, z, bb;
        return gap_at(t, grid_index(t), x, c, z, bb);
      },
      true, target, false, prune ? &kPruneEveryEighth : nullptr, screen);
  if (!path.creased() || std::abs(gap) > target || (screen && screen->coarse_only)) return gap;
  // The size of the distance above is max(|gap|, slide) at every sample, so its largest
  // value over the segment is the larger of the gap's (found above) and the slide's: the
  // slide is searched on its own, without the gap at its samples off the grid.
  //
  // Its finer samples are pruned (Pruning) below the gap, and only in the eighths of the
  // segment over which the path's own nose stays as it was: its states at the eighth's
  // ends (the blocks and the grid's every fourth line) both free, or both held at the same
  // crease on the same flank. Where they differ a hold begins, ends or changes flank in the
  // eighth, and the slide there can be a bump as narrow as what is left of the hold: every
  // sample is taken. Where they agree, a hold that begins and ends between them would be
  // shorter than the eighth and, rising from nothing at both its ends, low with it; the
  // peak's neighbours are sampled either way.
  AxisState coarse[9];
  coarse[0] = a;
  coarse[8] = b;
  // The rises at either end (Pruning::parts) at the grid's samples; 0 at the blocks.
  double rise[2][kGrid + 1];
  rise[0][0] = rise[1][0] = rise[0][kGrid] = rise[1][kGrid] = 0;
  // An eighth whose ends are both free can still hold a hold shorter than it, which can
  // change flank inside it, and the slide jumps there (a 0.1 mm nose on the compound eye:
  // errors down to 0.9 of the full measure): free throughout only where the two ends'
  // touches are clear of the creases by half as much again as they lie apart, which holds
  // the path's touches between them.
  struct TouchesClear final : EighthCheck {
    const Path& path;
    const RadialLine* lines;
    const AxisState* states;
    TouchesClear(const Path& p, const RadialLine* l, const AxisState* s)
        : path(p), lines(l), states(s) {}
    bool free_throughout(int k) const override {
      const AxisState &from = states[k], &to = states[k + 1];
      if (from.held) return true;  // held at one crease on one flank: the marks' own rule
      const RadialLine &at_from = lines[4 * k], &at_to = lines[4 * k + 4];
      const double apart = touches_apart(at_from, from.contact_r, at_to, to.contact_r);
      return block_touch_clear(path, at_from, from, 1.5 * apart) &&
             block_touch_clear(path, at_to, to, 1.5 * apart);
    }
  };
  const TouchesClear touches_clear(path, grid_line, coarse);
  Pruning pruning;
  pruning.parts[0] = rise[0];
  pruning.parts[1] = rise[1];
  if (prune) {
    for (int k = 1; k < 8; ++k)
      path.at(a.tau + static_cast<double>(4 * k) / kGrid * (b.tau - a.tau), grid_line[4 * k],
              coarse[k]);
    for (int k = 0; k < 8; ++k) {
      const AxisState &from = coarse[k], &to = coarse[k + 1];
      // Held at the same crease: where it crosses the radial line moves by no more than
      // twice the touch (a rim crossing the line at 63° or more to it; where the line runs
      // along a rim its crossings move fast and come close, and the eighth is sampled).
      const double moved =
          touches_apart(grid_line[4 * k], from.contact_r, grid_line[4 * k + 4], to.contact_r);
      // Both free: also only where the touches between are clear of the creases
      // (TouchesClear, above).
      pruning.eighth[k] =
          from.held == to.held &&
          (!from.held || (std::abs(to.crease_rho - from.crease_rho) <= 2 * moved &&
                          (from.contact_r > from.crease_rho) == (to.contact_r > to.crease_rho)));
    }
    pruning.floor = std::abs(gap);
    pruning.check = &touches_clear;
  }
  AxisState ideal;
  const double slide = largest_deviation(
      path,
      [&](double t) {
        double x, c, z, bb;
        motion.at(t, x, c, z, bb);
        const int j = grid_index(t);
        const double tau = a.tau + t * (b.tau - a.tau);
        if (j >= 0 && j % 4 == 0 && prune) {
          ideal = coarse[j / 4];  // the same state: its τ and line are the ones used there
        } else if (j >= 0) {
          path.at(tau, grid_line[j], ideal);
        } else {
          path.at(tau, line_at(tau), ideal);
        }
        double ends[2];
        const double above_path = path.slide(x, c, z, bb, ideal, ends);
        if (j >= 0) {
          rise[0][j] = ends[0];
          rise[1][j] = ends[1];
        }
        return std::max(above_path, 0.0);  // a nose below rises nowhere
      },
      true, target, false, prune ? &pruning : nullptr);
  // A gap below the design is a gouge whatever the slide: its sign is what the verdict
  // reads (chord_below). Only an unbounded measure (a step taken over the target) gets here
  // with one; the slide had hidden an axicon's apex cut 0.98 µm deep as a chord above it.
  if (gap < -path.stand_off()) return gap;
  return slide > std::abs(gap) ? slide : gap;
}

// The chord fields of the point that ends a segment, from its error as distribute()
// measures it (from the band's centre, the blocks' stand-off above the design). `floor`:
// how far above the design the motion must stay (the real edge's reach past the round
// nose); a segment that comes closer counts as below.
inline void set_chord(ContactPoint& p, const AxisState& s, double error, bool jump,
                      double stand_off, double floor) {
  p.stand_off = stand_off;
  p.chord_error = stand_off + std::abs(error);
  p.chord_below = error < floor - stand_off;
  p.chord_jump = jump;
  p.uncut_residual = s.uncut;
}

// How far the axes move between two states (mm): X, Z and the arc of C at their mean X.
inline double axis_travel(const AxisState& a, const AxisState& b) {
  const double arc = 0.5 * (std::abs(a.x_axis) + std::abs(b.x_axis)) * (b.c - a.c);
  return std::hypot(b.x_axis - a.x_axis, b.z - a.z, arc);
}
// Two blocks farther apart than the program's resolution (1 nm along X, Z and the arc of C):
// a nose held at a crease of a profile does not move, and its hold's end is no new block.
inline bool apart(const AxisState& a, const AxisState& b) {
  return axis_travel(a, b) > 1e-6;
}

// Where the nose begins or ends a hold at a crease (section_envelope.hpp) the axis motion
// kinks: the first state past the change in (a, b], until the states either side of it are
// within the program's resolution (`apart`: a kink placed closer than that to its block
// cannot be told from one on it) or within 1e-12 of τ apart (where the axes jump, they never
// come closer). A block there puts the kink on a block boundary, and the chords on either
// side follow smooth pieces (with a jump in held state the blocks on either side stay where
// they were).
//
// The bracket closes by a safeguarded secant, not by bisection alone (15 path states a
// change on the compound eye's chord cut; now 8). While the nose is held the path's own
// contact moves on past the held touch: path_r − contact_r grows smoothly from about 0 at
// the change. (It changes sign where the contact crosses the crease and the touch moves to
// the other flank: a held state across that from the latest tells nothing of this end, and
// is dropped.) The line through the held side's last two states gives the change's place;
// the state asked for is that estimate moved by 0.4 of the resolution toward the bracket's
// farther end, so that an estimate good to that closes the bracket from both sides in two
// states. An estimate that fell short (a free state, which says nothing of the gap) is
// moved a sixteenth of the way on toward the held end the next time, for a held state near
// the change. With one held state, the bracket's held end, the second is asked a sixteenth
// of the way in from it. After two such states that did not halve the bracket, or with no
// estimate inside it, the bracket is bisected. The bracket and the test that ends the
// search are bisection's: only which state in the last 1 nm the block takes differs.
template <class Path>
void end_at_hold_change(const Path& path, const AxisState& a, const AxisState& b,
                        AxisState& first_changed) {
  first_changed = b;
  AxisState last_same = a, mid;
  double lo = a.tau, hi = b.tau;
  // The held side's last two states: τ, and how far the path's contact has moved past the
  // held touch.
  double held_tau[2] = {0, 0}, held_gap[2] = {0, 0};
  int held_count = 0;
  const auto note_held = [&](const AxisState& s) {
    if (!s.held) return;
    const double gap = s.path_r - s.contact_r;
    held_tau[0] = held_tau[1];
    held_gap[0] = held_gap[1];
    held_tau[1] = s.tau;
    held_gap[1] = gap;
    held_count = held_count > 0 && held_gap[0] * gap <= 0 ? 1 : std::min(held_count + 1, 2);
  };
  note_held(a.held ? a : b);
  int slow_secants = 0;  // secant states in a row that did not halve the bracket
  bool fell_short = false;
  for (int it = 0;
       it < 60 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)) && apart(last_same, first_changed);
       ++it) {
    const double width = hi - lo;
    double t = 0.5 * (lo + hi);
    bool secant = false;
    if (slow_secants < 2 && held_count == 2 && held_gap[0] * held_gap[1] > 0 &&
        held_gap[0] != held_gap[1]) {
      double estimate =
          held_tau[1] - held_gap[1] * (held_tau[1] - held_tau[0]) / (held_gap[1] - held_gap[0]);
      if (fell_short) estimate += 0.0625 * ((a.held ? lo : hi) - estimate);
      // The resolution in τ: 1 nm of axis travel at the bracket's mean rate.
      const double travel = axis_travel(last_same, first_changed);
      const double resolution = travel > 0 ? 1e-6 * width / travel : 0.0;
      const double toward = estimate - lo > hi - estimate ? -1.0 : 1.0;
      const double asked = estimate + toward * 0.4 * resolution;
      if (asked > lo && asked < hi) {
        t = asked;
        secant = true;
      }
    } else if (slow_secants < 2 && held_count < 2) {
      // One held state, the bracket's held end: a second a sixteenth of the way in from it
      // (most changes lie well inside a trial; where this one does not, the bracket
      // shrinks sixteenfold instead).
      t = a.held ? lo + 0.0625 * width : hi - 0.0625 * width;
      secant = true;
    }
    path.at(t, mid);
    if (mid.held == a.held) {
      lo = mid.tau;
      last_same = mid;
    } else {
      hi = mid.tau;
      first_changed = mid;
    }
    note_held(mid);
    slow_secants = secant && hi - lo > 0.5 * width ? slow_secants + 1 : 0;
    fell_short = secant && !mid.held;
  }
}

// A jump: over a rejected step the programmed point moves this many times farther than the
// contact. Along a smooth offset it moves |1 + Rκ| times as far, a few at most; across a
// jump the ratio grows without bound as the step shrinks.
constexpr double kJumpRatio = 100;

// A trial segment whose coarse samples all lie within this fraction of the target of the
// band's centre grows the step unmeasured (distribute's pending trial): the model's growth,
// (target/error)^(1/2), reaches its cap of 16 below 1/259 of the target, and this leaves the
// finer samples a factor of 4 to exceed the coarse ones by.
constexpr double kGrowsOnCoarse = 1e-3;

// The equal-arc-length rule's next block after `current`: the step in τ whose chord
// between the two contacts is o.arc_length to 1e-8 (or the largest step, where the angle
// cap or the end binds), by proportional corrections from `step`, the last step taken
// (along a path they change slowly: two or three evaluations a block). The tight
// tolerance makes a block a function of the one before it alone, whatever the first guess:
// a band that walks from a seam follows the walk that placed it (spiral.cpp,
// equal_arc_seams), where a looser one let the two drift apart by a tenth of a step.
//
// The contact is not continuous everywhere: where the nose is held at a crease it touches
// one flank while the projection crosses the crease, then the other (section_envelope.hpp),
// and the contact jumps. So the corrections keep a bracket of steps short and long of the
// length, and bisect it where they would leave it. A bracket that closes on a jump takes
// the step just short of it; where that step would not move the block (the jump is at the
// start), the length counts from where the contact lands past the jump instead. `step`
// returns the step taken.
template <class Path>
void next_equal_arc_point(const Path& path, const CutterPointOptions& o, const AxisState& current,
                          double end, double& step, AxisState& trial) {
  const double remaining = end - current.tau;
  const auto advance = [&](double d) { return d >= remaining ? end : current.tau + d; };
  const double limit = std::min(path.cap(), remaining);
  step = std::min(step, limit);
  const double first_guess = step;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  Eigen::Vector3d from = current.point;
  double short_step = 0, long_step = kNone;
  AxisState short_state, long_state;
  bool landed = false;
  for (int it = 0; it < 100; ++it) {
    path.at(advance(step), trial);
    const double chord = (trial.point - from).norm();
    if (std::abs(chord - o.arc_length) <= 1e-8 * o.arc_length) return;
    if (chord < o.arc_length) {
      if (step >= limit) return;  // the cap or the end binds
      short_step = step;
      short_state = trial;
    } else {
      long_step = step;
      long_state = trial;
    }
    // A jump: the bracket closed on it, or no step is short of the length however short.
    if ((long_step < kNone && long_step - short_step <= 1e-9 * long_step) ||
        (short_step == 0 && long_step <= 1e-9 * first_guess)) {
      if (short_step > 0 && apart(short_state, current)) break;
      if (landed) break;
      landed = true;
      from = long_state.point;
      short_step = long_step;
      short_state = long_state;
      long_step = kNone;
      step = std::max(first_guess, 2 * short_step);
      continue;
    }
    double next = chord > 0 ? std::min(limit, step * o.arc_length / chord) : limit;
    if (!(next > short_step && next < long_step)) next = 0.5 * (short_step + long_step);
    if (next == step) break;
    step = next;
  }
  // Unconverged (a jump): the step just short of the length.
  if (short_step > 0 && trial.tau != short_state.tau) {
    step = short_step;
    trial = short_state;
  }
}

// The error a segment may reach: the band is [0, ε] above the design, its centre the
// blocks' stand-off, so each segment may bend ε − stand_off either way from it, less a
// margin for the sampled maximum.
inline double chord_target(const CutterPointOptions& o, double stand_off) {
  return 0.97 * (o.tolerance - stand_off);
}

// The path's last steps (docs/path.md, "The path's last steps"): the program stops after
// its last block, over that block's time, and at one spindle speed a last block of a few
// hundredths of a step asked C for 25 times the start's acceleration (the stop is
// v/t = ω²/Δθ). With `left` of τ to the path's end and steps of `step`, the step to take
// now: under linear motion the steps left are laid out as [(L − s)/2, (L − s)/2, s] for L
// in (2s, 2.5s) and [max(L − s, s/2), the rest] for L in (s, 2s], so that the last block
// is s where it can be and none of the last three is shorter than s/2. Under PVT the last
// two are evened instead, [L/2, L/2] for L in (s, 2s): with a last step longer than the
// one before, the last cubic (its end velocity one-sided) dipped 45.6 nm toward the ring
// profile's design (tests/path/nose_chord_test.cpp), to 4.4 nm above it from the 50 nm
// stand-off, where evened it dips 25.5 nm. `step` itself where nothing changes: beyond
// 2.5 steps, or within a millionth of a step of a whole number of them (the last sliver
// then joins the step before it, in distribute).
inline double last_step_laid_out(double left, double step, bool pvt) {
  const double whole = 1e-6 * step;
  if (pvt) return left > step + whole && left < 2 * step ? 0.5 * left : step;
  if (left > 2 * step + whole && left < 2.5 * step) return 0.5 * (left - step);
  if (left > step + whole && left <= 2 * step + whole)
    return std::min(step, std::max(left - step, 0.5 * step));
  return step;
}

// The part of an equal arc's step in τ its last steps are laid out in (distribute).
inline constexpr double kArcLayoutStep = 0.98;

// Where a piece of a PVT path meets the pieces either side (spiral.cpp plans bands at
// once). A cubic's velocity at a seam depends on blocks on both sides, so a piece either
// knows the blocks before its start (`before2`, `before`: a band planned again after the one
// before it) or judges its first segment over every block before it the other piece could
// place: a step back of up to the cap, on the path, or none (`open_start`). Likewise, a
// piece whose end is a seam judges its last segment over every next step up to the cap
// (`open_end`). Every judgement over such a range is at its ends and at the piece's own
// step (as the search judges a new segment at an equal next step, below): the error is
// convex in the velocity, which runs between them. The seam's true segments are judged again
// once both pieces are known (spiral.cpp).
struct PieceJoints {
  const AxisState* before2 = nullptr;
  const AxisState* before = nullptr;
  bool open_start = false;
  bool open_end = false;
};

// Walks τ from 0 to tau_end, calling emit(state, chord_error, jump) for every point, the
// chord error (of the segment that ends at the point) signed as segment_error's. `jump`
// marks a segment across which the programmed point jumps (the nose centre at a crease
// sharper than the nose: the offset of a concave crease is not the offset of either
// side): its error stops falling with the step, so the step search accepts a short step
// over it and reports the error as it is.
//
// PVT (pvt_rule.hpp): a segment's cubic depends on the blocks on either side, so the
// search for the next block b judges two segments. The one before it, (a₋, a), is final
// once b is chosen (b sets the velocity at a): it must stay within the target too, which
// keeps consecutive block times close wherever the path bends. The new one, (a, b), waits
// for the block after b to set the velocity at b. That velocity runs from the secant
// (b − a)/h, as the next step shrinks to nothing, to the velocity one equal step gives;
// the motion is affine in it, so its largest error is convex in it, and (a, b) is judged
// at both: whatever step the next search takes up to an equal one, (a, b) stays within
// the target, and a short enough next step always exists. It is judged finally when the
// next block is chosen, and emitted then: emission lags one block in PVT mode.
//
// A piece of the path: τ from `begin` to `end` (the whole path by default), its first point
// emitted only if `emit_begin` (a piece that continues another leaves that point to it);
// in PVT mode `joints` says what lies beyond its ends (PieceJoints above).
template <class Path, class Emit>
void distribute(Path& path, const CutterPointOptions& o, Emit&& emit, double begin = 0.0,
                double end = -1.0, bool emit_begin = true, const PieceJoints& joints = {}) {
  if (end < 0) end = path.tau_end();
  const bool pvt = o.interpolation == Interpolation::kCubic;
  // The last two blocks before `current` (PVT), and whether they exist.
  AxisState before2, before, current, trial, look, transition;
  AxisState shortened_trial;  // the chord rule's last steps laid out (below)
  bool has_before2 = false, has_before = false;
  if (pvt && joints.before) {
    before = *joints.before;
    has_before = true;
    if (joints.before2) {
      before2 = *joints.before2;
      has_before2 = true;
    }
  }
  path.at(begin, current);
  path.commit(current);
  // PVT: the τ of the block `current` stands for (its own, unless it is a still state).
  double block_tau = current.tau;
  if (emit_begin) emit(current, 0.0, false);
  if (!(end > begin)) return;
  // Chord error ∝ step^order: linear chords; PVT's central-difference velocities are
  // second-order, so its cubics are third-order.
  const double order = pvt ? 3.0 : 2.0;
  const double target = chord_target(o, path.stand_off());
  const double min_step = 1e-12 * std::max(1.0, end);
  double step = std::min(path.cap(), end - begin);
  // The chord rule's last step that nothing but the error set (not cut short at a hold
  // change, a jump, the cap or the end): the next search starts from it. A step that ends on a kink
  // says nothing of the error beyond it, and starting from such a sliver cost two or three
  // trials of growth, each measured in full near a rim.
  double natural_step = step;
  // A trial block's errors: of the new segment (current, trial) and, in PVT mode, of the
  // one before it as `trial` finalises it. The larger in size decides.
  double new_error = 0, previous_error = 0;
  // `cutoff`: a segment whose gap alone misses it is not measured further (segment_error).
  constexpr double kFull = std::numeric_limits<double>::infinity();
  // A PVT segment (a, b) with the blocks either side, signed error. Where a side is a seam
  // whose block there is not known (PieceJoints), the largest over the blocks it may be:
  // none (the secant), a step back (or on) of the segment's own length, or of the cap.
  AxisState joint_before[2], joint_after[2];
  const auto judge = [&](const AxisState* b0, const AxisState& a, const AxisState& b,
                         const AxisState* b3, double cutoff) {
    const bool open_before = !b0 && joints.open_start && a.tau == begin;
    const bool open_after = !b3 && joints.open_end && b.tau >= end;
    const AxisState* befores[3] = {b0, nullptr, nullptr};
    const AxisState* afters[3] = {b3, nullptr, nullptr};
    const double steps[2] = {b.tau - a.tau, path.cap()};
    if (open_before) {
      for (int k = 0; k < 2; ++k) {
        path.at(std::max(0.0, a.tau - steps[k]), joint_before[k]);
        befores[k + 1] = &joint_before[k];
      }
    }
    if (open_after) {
      for (int k = 0; k < 2; ++k) {
        path.at(std::min(path.tau_end(), b.tau + steps[k]), joint_after[k]);
        afters[k + 1] = &joint_after[k];
      }
    }
    const int n_before = open_before ? 3 : 1, n_after = open_after ? 3 : 1;
    double signed_worst = 0;
    for (int i = 0; i < n_before; ++i)
      for (int j = 0; j < n_after; ++j) {
        const double e =
            segment_error(path, Segment{befores[i], a, b, afters[j]}, o.interpolation, cutoff);
        if (std::abs(e) > std::abs(signed_worst)) signed_worst = e;
        if (std::abs(signed_worst) > cutoff) return signed_worst;
      }
    return signed_worst;
  };
  // `screen` (linear motion only): the chord search's screen of a trial (CoarseScreen).
  const auto measure = [&](const AxisState& t, double cutoff, CoarseScreen* screen = nullptr) {
    if (!pvt) {
      new_error = segment_error(path, Segment{nullptr, current, t, nullptr}, o.interpolation,
                                cutoff, screen);
      previous_error = 0;
      return std::abs(new_error);
    }
    const AxisState* known_before = has_before ? &before : nullptr;
    new_error = judge(known_before, current, t, nullptr, cutoff);
    double worst = std::abs(new_error);
    if (t.tau < end) {
      path.at(std::min(end, t.tau + (t.tau - current.tau)), look);
      const double equal_step = judge(known_before, current, t, &look, cutoff);
      worst = std::max(worst, std::abs(equal_step));
    }
    previous_error = 0;
    if (has_before) {
      // The segment to the block `current` stands for (below: a still state stands for
      // the block it repeats), over that block's own stretch of τ.
      AxisState block = current;
      block.tau = block_tau;
      previous_error = judge(has_before2 ? &before2 : nullptr, before, block, &t, cutoff);
    }
    return std::max(worst, std::abs(previous_error));
  };
  bool pending_jump = false;  // PVT: the jump flag of the segment that ends at `current`
  // PVT: the block `current` stands for, waiting in the lag, once the segment to it is
  // judged finally. A piece that continues another (with the blocks before it known)
  // leaves its first block to that one.
  const auto emit_current = [&] {
    if (has_before && (emit_begin || block_tau != begin))
      emit(current, previous_error, pending_jump);
  };
  // Equal angles: the step, and the index of the path's point at `begin`.
  const double angle_step = 2 * std::numbers::pi / std::max(1, o.points_per_revolution);
  const long long first_step = std::llround(begin / angle_step);
  long long steps_taken = 0;
  // This piece ends the whole path (not at a band's seam): its last steps are laid out
  // (last_step_laid_out). Equal angles leave their lattice from the first step laid out.
  const bool at_path_end = end >= path.tau_end();
  bool laying_out = false;
  while (current.tau < end) {
    const double remaining = end - current.tau;
    // The end is reached exactly, never by a sum that rounds short of it.
    const auto advance = [&](double d) { return d >= remaining ? end : current.tau + d; };
    const double limit = std::min(path.cap(), remaining);
    double error = 0;
    bool jump = false;
    if (o.rule == CutterPointRule::kEqualAngle) {
      // The path's j-th point at j·(2π/n), a product and not a running sum: the steps stay
      // equal to rounding however long the path, and across the seams of bands, which begin
      // on such a point (spiral.cpp, band_bounds).
      double next = static_cast<double>(first_step + ++steps_taken) * angle_step;
      // Near the path's end the steps left are laid out as the chord rule's are: the last
      // lattice step was what the turns left, often a sliver, and at one spindle speed the
      // stop after it set the whole program's speed (a tilted sphere at 120 steps a turn:
      // 2.14 rpm where its blocks allow 14.57).
      if (at_path_end) {
        const double laid = last_step_laid_out(remaining, angle_step, pvt);
        if (laying_out || laid < angle_step) {
          laying_out = true;
          next = current.tau + laid;
        }
      }
      path.at(next >= end ? end : next, trial);
      step = trial.tau - current.tau;
      measure(trial, kFull);
    } else if (o.rule == CutterPointRule::kEqualArcLength) {
      next_equal_arc_point(path, o, current, end, step, trial);
      // The last steps as the chord rule's, each only shorter than the arc's own step (the
      // rule's blocks are at most its length apart). Laid out in 0.98 of the step: the
      // step in τ the length gives drifts along the path, and a last step laid out as a
      // whole one fell a hair short of the end, then evened into two halves.
      if (at_path_end && trial.tau < end) {
        const double laid = last_step_laid_out(remaining, kArcLayoutStep * step, pvt);
        if (laid < kArcLayoutStep * step) {
          path.at(current.tau + laid, trial);
          step = trial.tau - current.tau;
        }
      }
      measure(trial, kFull);
    } else {
      // The largest step whose error is at most the target: e ∝ step^order locally, so
      // the secant-like update converges in a few evaluations.
      step = std::min(std::max(step, natural_step), limit);
      double accepted = 0;
      AxisState best;
      double best_new = 0, best_previous = 0;
      // PVT: the step with the smallest error, taken if none meets the target (its error
      // is then reported as it is, and the verdict judges it).
      AxisState least;
      double least_error = std::numeric_limits<double>::infinity(), least_step = 0;
      double least_new = 0, least_previous = 0;
      // The last rejected step: across a crease (a lenslet's rim) the error stops falling
      // with the step while the chord still spans the crease, so the local order is
      // measured and a step that barely helps is halved instead.
      double failed_step = 0, failed_error = 0;
      // The search keeps its bracket: the largest accepted step and the smallest rejected
      // one. A step the model predicts outside the bracket's inner 80 % is bisected
      // instead: near a rim the error is not a power of the step, and the model alone
      // could swing between two steps a few percent apart for all its iterations.
      double rejected = std::numeric_limits<double>::infinity();
      // The last accepted trial, for the local order of the error as the step grows.
      double grown_step = 0, grown_error = 0;
      bool exhausted = false;
      // A trial across a hold change (section_envelope.hpp: the kink where the nose begins
      // or ends a hold at a crease) is answered by the step that ends on the kink, tried
      // at once. The block goes there anyway whenever the final step holds the kink past
      // its first tenth (below, after the search); short of the kink the motion is smooth
      // and the model predicts well, while across it the error jumps with the step (0
      // just short of it, several times the target just past it on the compound eye), and
      // the bracket alone took five or more trials to close in on it. Linear motion only:
      // a PVT step also judges the segment before it.
      bool kink_measured = false, on_kink = false;
      double kink_step = -1;  // to `transition`, the hold change found (once a search)
      // A measured trial taken as the longest accepted step, with its errors.
      const auto take = [&](double taken_step, const AxisState& taken) {
        accepted = taken_step;
        best = taken;
        best_new = new_error;
        best_previous = previous_error;
      };
      // A trial whose coarse samples all lie within kGrowsOnCoarse of the target of the
      // centre (the base between a compound eye's lenslets turns as a surface of
      // revolution, and a chord there departs from it by rounding): the model would grow
      // the step by its largest factor whatever the finer samples showed, and the search
      // grows from it unmeasured. It is measured in full only if it is to be the block: when
      // a longer trial misses the target (or where the search ends on it). Before, such a
      // trial near a rim took a full measure, gap and slide, to say only "grow".
      AxisState pending;
      double pending_step = 0;
      bool screen_misled = false;
      // The pending trial measured in full, where it is still longer than the step accepted:
      // accepted as any trial that meets the target, or else the bracket's rejected end
      // (true then).
      const auto settle_pending = [&] {
        if (!(pending_step > accepted)) {
          pending_step = 0;
          return false;
        }
        const double e = measure(pending, target);
        if (e <= target) {
          take(pending_step, pending);
          grown_step = pending_step;
          grown_error = e;
          pending_step = 0;
          return false;
        }
        // Its finer samples found a peak its coarse ones missed: the rest of this search
        // measures every trial in full, as it did before the screen.
        rejected = std::min(rejected, pending_step);
        pending_step = 0;
        screen_misled = true;
        return true;
      };
      for (int it = 0; it < 80; ++it) {
        path.at(advance(step), trial);
        // The kink is tried before the trial itself: where it meets the target the block
        // goes there whatever the trial's error (below the target, it would move there
        // after the search; above it, the kink answers it), and the trial is not measured.
        bool kink_failed = false;
        if (!pvt && !kink_measured && trial.held != current.held) {
          // Found once; a later, shorter trial that still holds it past its first tenth
          // tries it then.
          if (kink_step < 0) {
            end_at_hold_change(path, current, trial, transition);
            kink_step = transition.tau - current.tau;
          }
          if (kink_step > 0.1 * step && kink_step < step &&
              kink_step > std::max(accepted, pending_step) && apart(transition, current) &&
              apart(transition, trial)) {
            kink_measured = true;
            if (measure(transition, target) <= target) {
              take(kink_step, transition);
              on_kink = true;
              break;
            }
            kink_failed = true;
          }
        }
        // Screened short of the cap, while the bracket is wider than the 3 % that ends the
        // search (a trial there would be the block), where the trial's end holds as its
        // start does (else the kink's rule above), and until a screen has misled.
        const bool screened =
            !pvt && !screen_misled && step < limit && trial.held == current.held &&
            (rejected == std::numeric_limits<double>::infinity() || rejected - step > 0.03 * step);
        CoarseScreen screen{kGrowsOnCoarse * target};
        error = measure(trial, target, screened ? &screen : nullptr);
        const bool coarse_only = screen.coarse_only;
        if (pvt && error < least_error) {
          least = trial;
          least_error = error;
          least_step = step;
          least_new = new_error;
          least_previous = previous_error;
        }
        // A trial past a kink whose step missed the target, and missing it too: the kink
        // bounds the bracket (where the trial meets it, the error is not monotonic there,
        // and the search goes on as it stands).
        if (kink_failed && error > target) rejected = std::min(rejected, kink_step);
        double next;
        if (coarse_only) {
          // Grown from as an accepted trial is, on its coarse value (pending, above).
          pending = trial;
          pending_step = step;
        } else if (error <= target) {
          if (step > accepted) take(step, trial);
          if (step >= limit || error >= 0.9 * target) break;
          // Growing again: the order of growth from the pending trial's full measure.
          if (pending_step > 0 && grown_step == pending_step)
            grown_error = measure(pending, target);
          if (step >= pending_step) pending_step = 0;  // a longer step met the target
        }
        if (error <= target) {
          if (error > 0) {
            // The error's order as measured over the last growth: where it grows slower
            // than the step's power (a segment whose error is mostly a hold's), the model's
            // order would creep toward the target by a few percent a trial.
            double local_order = order;
            if (grown_step > 0 && grown_step < step && grown_error > 0)
              local_order = std::log(error / grown_error) / std::log(step / grown_step);
            next = local_order < 0.5
                       ? 4 * step
                       : step * std::min(16.0, std::pow(target / error,
                                                        1 / std::min(local_order, order)) *
                                                   0.995);
          } else {
            next = limit;  // no measurable error: the cap, or the bracket's middle
          }
          grown_step = step;
          grown_error = error;
          next = std::min(next, limit);
        } else {
          rejected = std::min(rejected, step);
          double local_order = order;
          if (failed_step > 0 && failed_step != step && failed_error > 0)
            local_order = std::log(failed_error / error) / std::log(failed_step / step);
          next = local_order < 0.5
                     ? 0.5 * step
                     : step * std::max(0.2, 0.99 * std::pow(target / error,
                                                            1 / std::min(local_order, order)));
          failed_step = step;
          failed_error = error;
          // Rolling over a ridge the touch stays put while the axes move along the arc:
          // the path's own contact moves on, and the centre with it a few times as far.
          const double contact_move =
              (trial.point - current.point).norm() +
              (trial.rolling || current.rolling ? std::abs(trial.path_r - current.path_r) : 0.0);
          // The nose centre's move: a pivot L behind it swings L·ΔB where B follows a
          // turning normal (over a ridge, 60 mm × 0.5 rad), which is no jump.
          const double off = path.axis_offset();
          const double trial_x = trial.x_axis - off * std::sin(trial.b),
                       current_x = current.x_axis - off * std::sin(current.b);
          const double axes_move = std::hypot(
              trial_x - current_x,
              (trial.z - off * std::cos(trial.b)) - (current.z - off * std::cos(current.b)),
              0.5 * (std::abs(trial_x) + std::abs(current_x)) * (trial.c - current.c));
          if (axes_move > kJumpRatio * contact_move) {
            // This step crosses the jump. A shorter accepted one would only end before it,
            // and the next search would close in on it without end.
            take(step, trial);
            jump = true;
            break;
          }
          // A pending trial that misses the target as well bounds the bracket below this one.
          if (settle_pending() && next >= rejected) next = 0.5 * (accepted + rejected);
          if (accepted > 0 && next <= accepted) break;  // nothing between them is better
        }
        // The bracket's lower end: the longest step accepted, or pending.
        const double lower = std::max(accepted, pending_step);
        if (lower > 0 && rejected < std::numeric_limits<double>::infinity()) {
          const double width = rejected - lower;
          if (width <= 0.03 * lower) break;  // the accepted step is within 3 % of the best
          if (!(next >= lower + 0.1 * width && next <= rejected - 0.1 * width))
            next = lower + 0.5 * width;
        }
        if (next < min_step) {
          exhausted = true;
          break;
        }
        if (std::abs(next - step) <= 1e-6 * step && lower > 0) break;
        step = next;
      }
      settle_pending();  // the search ended on it (its 80 trials spent)
      // PVT takes its least error where the search ends short of the target, but not where
      // the step shrank to nothing: there no step helps (a nose larger than a trough, whose
      // centre turns back), the least error is that of a sliver, and the walk would crawl
      // on slivers without end. The path is not smooth there, as linear motion reports.
      if (accepted == 0 && pvt && least_step > 0 && !exhausted) {
        accepted = least_step;
        best = least;
        best_new = least_new;
        best_previous = least_previous;
      } else if (accepted == 0) {
        std::string why;
        if (exhausted) {
          why = path.why_not_smooth(current);
          if (why.empty()) why = "the path is not smooth here";
        }
        throw InputError("θ = " + std::to_string(current.c) +
                             " rad, r = " + std::to_string(current.contact_r) + " mm",
                         (exhausted ? "cannot meet the chord tolerance "
                                    : "no step meets the chord tolerance ") +
                             significant_text(o.tolerance * 1e3, 6) +
                             (exhausted ? " µm: " + why : " µm"),
                         "strategy.points.chord.tolerance");
      }
      trial = best;
      new_error = best_new;
      previous_error = best_previous;
      step = accepted;
      if (!jump && !on_kink && accepted < limit) natural_step = accepted;
      // Taken over the target (a jump, or PVT's least error): its gap alone was measured.
      if (std::max(std::abs(new_error), std::abs(previous_error)) > target) {
        measure(trial, kFull);
      } else if (trial.held != current.held && !jump && !on_kink && !kink_measured) {
        end_at_hold_change(path, current, trial, transition);
        // Not within a tenth of the step of its start: a block there would leave a sliver
        // of a segment, which only demands more of the axes at one speed. Anywhere later
        // the block moves back onto the kink (the step shortens by at most what is left
        // of it, and the next step starts on the kink); within 1 nm of the trial, the
        // trial is the block.
        const double at = (transition.tau - current.tau) / step;
        if (at > 0.1 && apart(transition, current) && apart(transition, trial) &&
            measure(transition, target) <= target) {
          trial = transition;
          step = trial.tau - current.tau;
        } else {
          new_error = best_new;  // measure(transition) may have replaced them
          previous_error = best_previous;
        }
      }
      // The path's last blocks (the whole path's end, not a band's seam), laid out by
      // last_step_laid_out. Each shortened step is measured as any trial and taken only
      // within the target; the next search finds its own step.
      if (o.rule == CutterPointRule::kChordError && at_path_end && !jump && !on_kink &&
          trial.tau < end && trial.held == current.held && step >= min_step) {
        const double shortened = last_step_laid_out(end - current.tau, step, pvt);
        if (shortened < step) {
          path.at(current.tau + shortened, shortened_trial);
          const double saved_new = new_error, saved_previous = previous_error;
          if (apart(shortened_trial, current) && measure(shortened_trial, target) <= target) {
            trial = shortened_trial;
            step = trial.tau - current.tau;
          } else {
            new_error = saved_new;
            previous_error = saved_previous;
          }
        }
      }
    }
    // A last sliver shorter than a millionth of a step joins this one instead. Under
    // equal arc lengths, one shorter than a hundredth: a band's end is a point of the same
    // rule's walk (spiral.cpp, equal_arc_seams), which the band's own points follow to
    // the rule's tolerance, not to the bit.
    const double sliver = o.rule == CutterPointRule::kEqualArcLength ? 1e-2 : 1e-6;
    if (end - trial.tau < sliver * step && trial.tau < end) {
      path.at(end, trial);
      // A sliver is short along τ, not always along the axes: where the centre jumps in
      // it (nothing rolled it over a ridge), the joined segment misses the tolerance, and
      // is counted as the jump it is. The other rules have no tolerance to miss (`target`
      // is the chord rule's): a profile's last equal arc, joined, read its dip as a jump
      // once its blocks stood off the design.
      const double joined = measure(trial, kFull);
      if (o.rule == CutterPointRule::kChordError && joined > target) jump = true;
    }
    path.commit(trial);
    // A nose held still at a crease over the whole step (a profile's trough narrower than
    // the nose): the block would repeat the last one's place, a move of no length and no
    // time. The walk goes on from it; nothing is emitted. In PVT mode the same, where a
    // block's time is its X-Z chord (Path::holds_still): a controller's velocity at a
    // block is a difference over its neighbours' times, which three blocks in one place
    // leave none of. The still state then stands for the block it repeats, still waiting
    // in the lag: the segment to it was judged with it as the next block, whose place (and
    // so the velocity it gives) is the same to the program's resolution. That segment is
    // judged again, once the next block is known, over the block's own stretch of τ
    // (`block_tau`): over the still state's, the path's nose would stand at the block's
    // place while the motion is still on its way there.
    // Only where the path holds still: on the spiral C advances with τ, and a nose held on
    // the axis (X = 0, so no arc of C counts in `apart`) still turns the part under its
    // edge. Dropped as still, such a block had left a segment twice the cap whose middle
    // went 7 nm into a sinusoidal grid (docs/path.md, "Blocks that do not move").
    const bool still = path.holds_still() && !apart(current, trial);
    if (!pvt) {
      current = trial;
      if (!still) emit(current, new_error, jump);
      continue;
    }
    if (still) {
      current = trial;
      // The program's last block, the one it repeats: the segment to it was judged with
      // the velocity this still block gives, the one-sided one of the end.
      if (current.tau >= end) emit_current();
      continue;
    }
    emit_current();
    block_tau = trial.tau;
    before2 = before;
    has_before2 = has_before;
    before = current;
    has_before = true;
    current = trial;
    pending_jump = jump;
    if (current.tau >= end) emit(current, new_error, jump);  // measured one-sided: final
  }
}

}  // namespace freeturn::detail
