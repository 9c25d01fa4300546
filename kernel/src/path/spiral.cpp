#include "freeturn/path/spiral.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/core/ordered_parallel.hpp"
#include "freeturn/core/parallel_for.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "freeturn/surface/height_field_queries.hpp"
#include "nose_section.hpp"
#include "path_stepper.hpp"
#include "section_prediction.hpp"

namespace freeturn {
namespace {

std::string where(double theta, double r) {
  return "θ = " + std::to_string(theta) + " rad (" + std::to_string(theta * 180 / std::numbers::pi) +
         "°), r = " + std::to_string(r) + " mm";
}

// τ = θ. The base point at arc length s(θ), moved along the base normal to the design.
class SpiralPath {
 public:
  SpiralPath(const Surface& design, const BaseSurface& base, const SpiralOptions& o)
      : design_(design),
        base_(base),
        o_(o),
        nose_(design, o.tool, stand_off_for(o.points, o.tool, design)),
        b_(o.pitch / (2 * std::numbers::pi)) {
    s_outer_ = base.arc_length(o.outer_radius);
    s_inner_ = base.arc_length(o.inner_radius);
    end_ = (s_outer_ - s_inner_) / b_;
    if (!base.is_plane()) {
      // Projected along the base normal, the base's own radius is not the contact's: the
      // ends' arc lengths are solved so that the first and last contacts lie on the
      // aperture's radii (paper 000 spirals the base; the aperture bounds the design).
      s_outer_ = end_arc_length(o.outer_radius, s_outer_, true);
      if (o.inner_radius > 0) s_inner_ = end_arc_length(o.inner_radius, s_inner_, false);
      end_ = (s_outer_ - s_inner_) / b_;
    }
  }

  double tau_end() const { return end_; }
  double cap() const { return o_.points.max_angle_step; }
  // At one spindle speed a block's time is its angle (pvt_rule.hpp).
  double block_time(const detail::AxisState& a, const detail::AxisState& b) const {
    return b.tau - a.tau;
  }
  bool creased() const { return design_.has_creases(); }
  bool holds_still() const { return false; }  // C advances with τ: a held nose moves too
  // With a nose the gap's kinks where creases pass are concave (peak_may_lie_in); without
  // one the contact's own distance kinks either way at a crease.
  bool prune_samples() const { return nose_.nose_radius() > 0 && !o_.take_every_sample; }
  double stand_off() const { return nose_.stand_off(); }
  double chord_floor() const { return nose_.chord_floor(); }
  double axis_offset() const { return nose_.axis_offset(); }
  double pitch() const { return o_.pitch; }
  std::string why_not_smooth(const detail::AxisState& s) const {
    return nose_.why_not_smooth(RadialLine(s.c), s.contact_r);
  }

  double deviation(double x_axis, const RadialLine& c, double z, double b, double hint_r) const {
    return nose_.deviation(x_axis, c, z, b, hint_r);
  }
  double deviation_near_hint(double x_axis, const RadialLine& c, double z, double b, double hint_r,
                             double& touch_rho) const {
    return nose_.deviation_near_hint(x_axis, c, z, b, hint_r, touch_rho);
  }
  bool touch_clear(const RadialLine& c, double rho, double margin) const {
    return !o_.measure_every_crease && nose_.touch_clear(c, rho, margin);
  }
  // The next turns lie a pitch away on either side: each turn cuts half a pitch either way.
  double slide(double x_axis, double, double z, double b, const detail::AxisState& ideal,
               double* ends = nullptr) const {
    return nose_.slide(x_axis, z, b, ideal.x_axis, ideal.z, ideal.b, ideal.contact_r, ideal.slope,
                       0.5 * o_.pitch, ends);
  }

  void at(double theta, detail::AxisState& s) const { evaluate(theta, RadialLine(theta), s); }
  void at(double theta, const RadialLine& line, detail::AxisState& s) const {
    evaluate(theta, line, s);
  }
  void commit(const detail::AxisState& s) { lambda_ = s.warm; }

  BasePoint base_point(double theta) const {
    // The ends are exact radii, not the inverse of an arc length.
    const double s = o_.centre_to_edge ? s_inner_ + b_ * theta : s_outer_ - b_ * theta;
    if (base_.is_plane()) {
      if (theta <= 0) return base_.at_radius(o_.centre_to_edge ? o_.inner_radius : o_.outer_radius);
      if (theta >= end_) return base_.at_radius(o_.centre_to_edge ? o_.outer_radius : o_.inner_radius);
    }
    return base_.at_arc_length(std::clamp(s, s_inner_, s_outer_));
  }

 private:
  // The base's arc length whose projection along the base normal lands on the contact
  // radius `target` at the spiral's end there (θ = 0 at the start, the last θ at the end,
  // which itself moves with the arc length): secant iterations from `guess`, within the
  // base, or the base continued along its edge tangent by up to 5% of its length.
  double end_arc_length(double target, double guess, bool outer) const {
    const double total = 1.05 * base_.total_arc_length();
    const auto miss = [&](double arc) {
      const double theta =
          outer == o_.centre_to_edge ? (outer ? arc - s_inner_ : s_outer_ - arc) / b_ : 0.0;
      const BasePoint bp = base_.at_arc_length(arc);
      const RadialLine line(theta);
      const HeightFieldHit hit = intersect_ray(design_, BaseSurface::point(bp, line),
                                               BaseSurface::normal(bp, line), 0.0);
      if (hit.status != Status::kOk || !hit.point.allFinite())
        throw InputError(where(theta, bp.rho),
                         "the projection along the base normal misses the design surface",
                         "strategy.spiral");
      return hit.point.x() * line.cos + hit.point.y() * line.sin - target;
    };
    double a = guess, fa = miss(a);
    double b = std::clamp(guess - fa, 0.0, total), fb = b == a ? fa : miss(b);
    for (int it = 0; it < 30 && std::abs(fb) > 1e-12 && fb != fa; ++it) {
      const double next = std::clamp(b - fb * (b - a) / (fb - fa), 0.0, total);
      a = b;
      fa = fb;
      b = next;
      fb = miss(b);
    }
    return b;
  }

  // line: the radial line at θ.
  void evaluate(double theta, const RadialLine& line, detail::AxisState& s) const {
    const BasePoint bp = base_point(theta);
    s.tau = theta;
    s.c = theta;
    const double c = line.cos, sn = line.sin;
    double contact_r, z, zx, zy;
    if (base_.is_plane()) {
      contact_r = bp.rho;
      design_.sag_gradient(contact_r * c, contact_r * sn, z, zx, zy);
      if (!std::isfinite(z))
        throw InputError(where(theta, bp.rho), "the design surface is undefined here",
                         "aperture.outer_radius");
    } else {
      const Eigen::Vector3d origin = BaseSurface::point(bp, line);
      const Eigen::Vector3d direction = BaseSurface::normal(bp, line);
      const HeightFieldHit hit = intersect_ray(design_, origin, direction, lambda_);
      if (hit.status != Status::kOk || !hit.point.allFinite())
        throw InputError(where(theta, bp.rho),
                         "the projection along the base normal misses the design surface",
                         "strategy.spiral");
      s.warm = hit.t;
      // The base normal lies in the radial plane at θ, so the contact does too.
      contact_r = std::max(0.0, hit.point.x() * c + hit.point.y() * sn);
      z = hit.point.z();
      if (nose_.nose_radius() + nose_.stand_off() == 0 && !nose_.b_follows()) {
        s.contact_r = contact_r;
        s.point = hit.point;
        s.x_axis = contact_r;
        s.z = z;
        s.held = false;
        s.uncut = 0;
        return;
      }
      zx = hit.zx;
      zy = hit.zy;
    }
    // Where a crease is under the nose, the nose may be held touching both its flanks.
    const NoseTouch touch = nose_.touch(line, contact_r, z, zx * c + zy * sn);
    s.contact_r = touch.rho;
    s.point = {touch.rho * c, touch.rho * sn, touch.z};
    s.slope = touch.slope;
    s.held = touch.held;
    s.uncut = touch.held ? touch.uncut : 0.0;
    s.crease_rho = touch.held ? touch.crease_rho : 0.0;
    s.rolling = touch.rolling;
    s.at_ridge = touch.at_ridge;
    s.path_r = contact_r;
    s.spread = touch.spread;
    nose_.axes(touch.rho, touch.z, touch.slope, s.x_axis, s.z, s.b);
  }

  const Surface& design_;
  const BaseSurface& base_;
  const SpiralOptions& o_;
  detail::NoseSection nose_;
  double b_, s_outer_ = 0, s_inner_ = 0, end_ = 0;
  double lambda_ = 0;  // the committed point's projection distance
};

// The last band is at least this many steps (the cap, or the equal angle) long: the path's
// last steps are laid out within it (path_stepper.hpp, last_step_laid_out, over up to 2.5
// steps), and a seam a sliver before the end had left the last band only that sliver.
constexpr double kLastBandSteps = 4;

// The spiral is planned in bands, each from a cold start at its first angle and ending
// exactly at its last, so that bands can be planned at once on several threads and the
// points stay the same on any number (docs/path.md, "Bands"). About 64 bands over the
// path, each one to four turns and a radian: a band is held whole until its turn to be
// consumed, so its length, not the path's, bounds the memory. PVT programs are banded
// likewise, their seams judged once both bands are known (plan_spiral). Equal angles are
// banded by whole turns, seams on the steps' own angles; equal arc lengths at points of
// one walk of the rule (equal_arc_seams below), so that no step is cut short at a seam. A
// path of one band streams to the sink.
std::vector<double> band_bounds(double end, const CutterPointOptions& points) {
  constexpr double kTurn = 2 * std::numbers::pi;
  std::vector<double> bounds{0.0};
  const double turns = std::clamp(std::ceil(end / kTurn / 64), 1.0, 4.0);
  if ((points.rule == CutterPointRule::kChordError ||
       points.rule == CutterPointRule::kEqualArcLength) &&
      end > kTurn) {
    // n turns and about a radian: a seam's block stays off the round angles θ = 2πk, where
    // a sampler that brackets C by whole turns can miss the block by rounding. Chord
    // control: in whole steps of the angle cap, each seam the j-th cap's angle j·cap, so
    // that where the cap binds throughout (a smooth part, a coarse tolerance) the steps stay
    // equal across the seams, as a dialect with one block time (`block_times: constant`)
    // needs. Where the cap divides a turn into N steps, the band's count of steps is kept
    // prime to N, so a seam meets a whole turn only at the N-th band (the cap at 5.6° or
    // more, with 64 bands or more).
    const double width = kTurn * turns + 1.0;
    if (points.rule == CutterPointRule::kChordError) {
      const double cap = points.max_angle_step;
      long per_band = std::max(1L, std::lround(width / cap));
      const double per_turn = kTurn / cap;
      const long n = std::lround(per_turn);
      if (n > 1 && std::abs(per_turn - static_cast<double>(n)) <= 1e-9 * per_turn)
        while (std::gcd(per_band, n) != 1) ++per_band;
      for (long k = 1; static_cast<double>(k * per_band) * cap < end - kLastBandSteps * cap; ++k)
        bounds.push_back(static_cast<double>(k * per_band) * cap);
    } else {
      const double last = end - kLastBandSteps * points.max_angle_step;
      for (int k = 1; k * width < last; ++k) bounds.push_back(k * width);
    }
  } else if (points.rule == CutterPointRule::kEqualAngle && end > kTurn) {
    // Equal angles: bands of whole turns, each seam the j-th step's angle j·(2π/n), so the
    // steps stay equal across it (to rounding, as they are along one band).
    const double step = kTurn / points.points_per_revolution;
    const long per_band = static_cast<long>(turns) * points.points_per_revolution;
    for (long k = 1; static_cast<double>(k * per_band) * step < end - kLastBandSteps * step; ++k)
      bounds.push_back(static_cast<double>(k * per_band) * step);
  }
  bounds.push_back(end);
  return bounds;
}

// Equal arc lengths: the bands' seams are points of one walk of the whole path by the
// rule, the first at or past each of `nominal`'s inner bounds. The walk places points
// only, measuring no chord: four path evaluations a point against the hundred or so a
// measured point costs on a creased design, so it holds the bands back little. Each band
// then walks from its seam to the next one by the same rule and lands on it, so every step
// is the rule's own, across the seams too (the band's points follow the walk's to rounding;
// a remainder under a hundredth of a step joins the last one: path_stepper.hpp). The walk
// depends on the path alone: the seams are the same on any number of threads.
std::vector<double> equal_arc_seams(const SpiralPath& path, const CutterPointOptions& points,
                                    const std::vector<double>& nominal) {
  const double end = nominal.back();
  std::vector<double> bounds{nominal.front()};
  SpiralPath walker = path;
  detail::AxisState current, next;
  walker.at(nominal.front(), current);
  walker.commit(current);
  double step = std::min(walker.cap(), end - nominal.front());
  std::size_t k = 1;
  while (k + 1 < nominal.size() && current.tau < end) {
    detail::next_equal_arc_point(walker, points, current, end, step, next);
    walker.commit(next);
    current = next;
    // A seam near the end would leave a band too short to lay out the last steps in.
    if (current.tau >= nominal[k] && end - current.tau > kLastBandSteps * walker.cap()) {
      bounds.push_back(current.tau);
      while (k + 1 < nominal.size() && nominal[k] <= current.tau) ++k;
    }
  }
  bounds.push_back(end);
  return bounds;
}

}  // namespace

PathSummary plan_spiral(const Surface& design, const BaseSurface& base,
                        const SpiralOptions& o, ContactSink& sink) {
  if (!(o.pitch > 0)) throw InputError("pitch", "must be > 0 mm per revolution");
  if (!(o.outer_radius > o.inner_radius && o.inner_radius >= 0))
    throw InputError("aperture", "needs 0 ≤ inner radius < outer radius");
  if (o.outer_radius > base.rho_max() * (1 + 1e-12))
    throw InputError("", "the base surface ends at ρ = " + std::to_string(base.rho_max()) +
                                     " mm, inside the outer radius",
                     "aperture.outer_radius");
  if (o.points.rule == CutterPointRule::kEqualAngle && o.points.points_per_revolution < 3)
    throw InputError("points_per_revolution", "must be at least 3");
  // A design whose sections meet more creases under the nose than its envelope follows
  // stops here, not after the revolutions outside that radius.
  double many_r = 0, many_theta = 0;
  if (!crease_lists_whole_under_nose(design, o.tool.nose_radius, o.inner_radius, o.outer_radius,
                                     many_r, many_theta))
    throw InputError(where(many_theta, many_r), detail::too_many_creases_under_nose(many_r),
                     "tool.nose_radius");
  forget_thread_warm_starts();
  const SpiralPath path(design, base, o);
  std::vector<double> bounds = band_bounds(path.tau_end(), o.points);
  if (o.points.rule == CutterPointRule::kEqualArcLength && bounds.size() > 2) {
    forget_thread_warm_starts();  // the walk's bits may not depend on the thread's past
    bounds = equal_arc_seams(path, o.points, bounds);
  }
  const long bands = static_cast<long>(bounds.size()) - 1;
  struct Band {
    std::vector<ContactPoint> points;
    std::vector<char> jumps;
    std::vector<detail::AxisState> head, tail;  // PVT: its first two and last three blocks
  };
  const bool pvt = o.points.interpolation == Interpolation::kCubic;
  // A point of the path as the sink takes it, with its section and scallop predicted.
  const auto contact_point = [&](const SpiralPath& piece, const detail::AxisState& s, double error,
                                 bool jump) {
    ContactPoint p;
    p.theta = s.c;
    p.r = s.contact_r;
    p.point = s.point;
    detail::set_chord(p, s, error, jump, piece.stand_off(), piece.chord_floor());
    const double zr =
        detail::fill_section(design, p, s.rolling || s.at_ridge ? &s.slope : nullptr, s.at_ridge);
    // Adjacent turns are p apart along the base's generating curve; on the design
    // they are p / cos β apart, β the angle between the two sections' tangents.
    const BasePoint bp = piece.base_point(s.c);
    const double cos_beta = (1 + bp.slope * zr) /
                            (std::sqrt(1 + bp.slope * bp.slope) * std::sqrt(1 + zr * zr));
    // Rolling over a ridge the touches spread further apart (NoseTouch::spread).
    p.pass_spacing = o.pitch / cos_beta * s.spread;
    p.scallop = detail::scallop_height(p.pass_spacing, p.section_curvature, o.tool.nose_radius);
    return p;
  };
  ContactChunker out(sink);
  PathSummary summary;
  const auto consume = [&](const ContactPoint& p, bool jump) {
    summary.add(p.theta, p.r, p.chord_error, jump);
    summary.theta_end = p.theta;
    summary.max_scallop = std::max(summary.max_scallop, p.scallop);
    summary.max_pass_spacing = std::max(summary.max_pass_spacing, p.pass_spacing);
    out.push(p);
  };
  if (bands == 1) {
    // One band (a path of a turn or so): there is nothing to put in order, so its points
    // go straight to the sink and memory stays flat however long the path is.
    forget_thread_warm_starts();  // as a band would: the path's set-up used them
    SpiralPath piece = path;
    detail::distribute(
        piece, o.points,
        [&](const detail::AxisState& s, double error, bool jump) {
          consume(contact_point(piece, s, error, jump), jump);
        },
        bounds[0], bounds[1], true);
    out.flush();
    return summary;
  }
  // A band planned from the seam at bounds[k]; in PVT mode with the blocks before it when
  // known (`joints`), else judging its seams over every block the next band may place.
  const auto plan_band_from = [&](long k, Band& band, const detail::PieceJoints& joints) {
    band.points.clear();
    band.jumps.clear();
    band.head.clear();
    band.tail.clear();
    forget_thread_warm_starts();  // the band's bits may not depend on the thread's past
    SpiralPath piece = path;
    detail::distribute(
        piece, o.points,
        [&](const detail::AxisState& s, double error, bool jump) {
          band.points.push_back(contact_point(piece, s, error, jump));
          band.jumps.push_back(jump ? 1 : 0);
          if (!pvt) return;
          if (band.head.size() < 2) band.head.push_back(s);
          if (band.tail.size() == 3) band.tail.erase(band.tail.begin());
          band.tail.push_back(s);
        },
        bounds[static_cast<std::size_t>(k)], bounds[static_cast<std::size_t>(k) + 1], k == 0,
        joints);
  };
  const auto plan_band = [&](long k, Band& band) {
    detail::PieceJoints joints;
    joints.open_start = pvt && k > 0;
    joints.open_end = pvt && k + 1 < bands;
    plan_band_from(k, band, joints);
  };
  // PVT seams (detail::PieceJoints): the two segments either side of a seam depend on both
  // bands, and each band judged its own over every block the other might place. Once both
  // are known they are judged as they are: a seam whose segments miss the target (the
  // ranges' judgement is at their ends and the band's step only) has the later band
  // planned again, from the blocks before the seam, on this thread. The band's first and
  // the seam's own block then report their segments' true errors. Equal angles and arc
  // lengths place their blocks whatever the errors: planned again, a band would place the
  // same ones, so their seams are judged and reported, not planned again.
  const bool steps_fixed = o.points.rule != CutterPointRule::kChordError;
  const double target = detail::chord_target(o.points, path.stand_off());
  std::vector<detail::AxisState> last_blocks;  // the path's last three blocks so far
  ContactPoint seam_point;                      // the last band's last point, held back
  bool seam_jump = false, holding = false;
  long replanned = 0;
  const auto segment = [&](const detail::AxisState* b0, const detail::AxisState& a,
                           const detail::AxisState& b, const detail::AxisState* b3) {
    return detail::segment_error(path, detail::Segment{b0, a, b, b3}, Interpolation::kCubic,
                                 std::numeric_limits<double>::infinity());
  };
  const auto join = [&](long k, Band& band) {
    forget_thread_warm_starts();  // the seam's judgement may not depend on this thread's past
    const std::size_t m = last_blocks.size();
    const detail::AxisState* before2 = m >= 3 ? &last_blocks[m - 3] : nullptr;
    const detail::AxisState& before = last_blocks[m - 2];
    const detail::AxisState& seam = last_blocks[m - 1];
    double into = 0, out_of = 0;
    const auto judge_seam = [&] {
      const detail::AxisState* after2 = band.head.size() > 1 ? &band.head[1] : nullptr;
      into = segment(before2, before, seam, &band.head[0]);
      out_of = segment(&before, seam, band.head[0], after2);
    };
    judge_seam();
    if ((!steps_fixed && std::max(std::abs(into), std::abs(out_of)) > target) ||
        band.head.size() < 2 || o.replan_every_seam) {
      detail::PieceJoints joints;
      joints.before2 = before2;
      joints.before = &before;
      joints.open_end = k + 1 < bands;
      plan_band_from(k, band, joints);
      ++replanned;
      judge_seam();
    }
    seam_point = contact_point(path, seam, into, seam_jump);
    band.points[0] = contact_point(path, band.head[0], out_of, band.jumps[0] != 0);
  };
  const int threads = std::min<long>(thread_count(o.threads), bands);
  ordered_parallel<Band>(threads, bands, 2 * threads, plan_band, [&](long k, Band& band) {
    if (!pvt) {
      for (std::size_t i = 0; i < band.points.size(); ++i) consume(band.points[i], band.jumps[i] != 0);
      return;
    }
    if (band.points.empty()) throw InputError(where(bounds[static_cast<std::size_t>(k)], 0),
                                              "a band of the spiral has no block", "strategy");
    if (holding) {
      join(k, band);
      consume(seam_point, seam_jump);
    }
    const std::size_t keep = k + 1 < bands ? band.points.size() - 1 : band.points.size();
    for (std::size_t i = 0; i < keep; ++i) consume(band.points[i], band.jumps[i] != 0);
    holding = keep < band.points.size();
    if (holding) {
      seam_point = band.points.back();
      seam_jump = band.jumps.back() != 0;
    }
    for (const detail::AxisState& s : band.tail) {
      if (last_blocks.size() == 3) last_blocks.erase(last_blocks.begin());
      last_blocks.push_back(s);
    }
  });
  out.flush();
  summary.replanned_seams = replanned;
  return summary;
}

}  // namespace freeturn
