#pragma once
// The cutter-point rules (cutter_points.hpp) over any path with a monotonic parameter τ
// and machine axes X (radius), C (spindle angle), Z (axial) as functions of τ. Internal to
// the path module: spiral.cpp and profile.cpp supply the path.
//
// A Path provides:
//   double tau_end() const;
//   void at(double tau, AxisState& s);      // may throw InputError (a missed projection)
//   void commit(const AxisState& s);        // the accepted point: the next warm start
//   double cap() const;                     // the largest step in τ
//   double deviation(double x_axis, double c, double z, double b, double hint_r) const;
//                                           // distance of the tool at these axes from the
//                                           // design; hint_r: the contact radius nearby
//   double angle_per_tau() const;           // dC/dτ (1 on a spiral, 0 in profile mode)
//   bool creased() const;                   // the design has creases (Surface::has_creases)
//   double stand_off() const;               // where the blocks stand off the design (mm):
//                                           // the centre of the tolerance band

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/path/contact_point.hpp"
#include "freeturn/path/cutter_points.hpp"

namespace freeturn::detail {

struct AxisState {
  double tau = 0;
  double x_axis = 0, c = 0, z = 0;  // X, C, Z of the programmed point (nose_section.hpp)
  double b = 0;                     // B (rad) when it follows the normal, else 0
  double contact_r = 0;             // the contact's signed radius in the radial plane at C
  double dx = 0, dz = 0, db = 0;    // dX/dτ, dZ/dτ, dB/dτ (cubic interpolation only)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double uncut = 0;  // mm: material the nose, held at a crease, leaves (section_envelope.hpp)
  double warm = 0;  // the path's warm start for the next point (a projection distance)
};

// The machine's position a fraction t of the way from block a to block b.
inline void interpolate(const AxisState& a, const AxisState& b, double t, Interpolation mode,
                        double angle_per_tau, double& x, double& c, double& z, double& bb) {
  if (mode == Interpolation::kLinear) {
    x = a.x_axis + t * (b.x_axis - a.x_axis);
    c = a.c + t * (b.c - a.c);
    z = a.z + t * (b.z - a.z);
    bb = a.b + t * (b.b - a.b);
    return;
  }
  // Cubic Hermite on each axis, tangents scaled by the segment's length in τ.
  const double h = b.tau - a.tau, t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  x = h00 * a.x_axis + h10 * h * a.dx + h01 * b.x_axis + h11 * h * b.dx;
  z = h00 * a.z + h10 * h * a.dz + h01 * b.z + h11 * h * b.dz;
  bb = h00 * a.b + h10 * h * a.db + h01 * b.b + h11 * h * b.db;
  c = h00 * a.c + h10 * h * angle_per_tau + h01 * b.c + h11 * h * angle_per_tau;
}

// The largest distance of the interpolated motion from the band's centre (the design
// raised by the path's stand-off) over one segment, signed (> 0: above it; < 0: below,
// and below the design itself where it passes the stand-off): samples (8 intervals; 32
// on a surface with creases, where the peak is a sharp tent at the crease), then a
// parabola through the largest and its neighbours. Where the parabola mispredicts the
// value at its own vertex, the deviation is not smooth there and a golden-section search
// of the bracket finds the peak instead.
template <class Path>
double segment_error(const Path& path, const AxisState& a, const AxisState& b,
                     Interpolation mode) {
  constexpr int kMaxIntervals = 32;
  const int intervals = path.creased() ? kMaxIntervals : 8;
  const double k = path.angle_per_tau();
  double signed_worst = 0;
  const auto deviation_at = [&](double t) {
    double x, c, z, bb;
    interpolate(a, b, t, mode, k, x, c, z, bb);
    const double d = path.deviation(x, c, z, bb, a.contact_r + t * (b.contact_r - a.contact_r)) -
                     path.stand_off();
    if (std::abs(d) > std::abs(signed_worst)) signed_worst = d;
    return std::abs(d);
  };
  double e[kMaxIntervals + 1];
  e[0] = e[intervals] = 0;  // the blocks themselves lie on the design
  int best = 1;
  for (int j = 1; j < intervals; ++j) {
    e[j] = deviation_at(static_cast<double>(j) / intervals);
    if (e[j] > e[best]) best = j;
  }
  const double denominator = e[best - 1] - 2 * e[best] + e[best + 1];
  if (!(denominator < 0)) return signed_worst;
  const double shift = std::clamp(0.5 * (e[best - 1] - e[best + 1]) / denominator, -1.0, 1.0);
  const double predicted = e[best] - 0.25 * (e[best - 1] - e[best + 1]) * shift;
  const double at_vertex = deviation_at((best + shift) / intervals);
  if (std::abs(at_vertex - predicted) <= (path.creased() ? 1e-3 : 1e-2) * predicted)
    return signed_worst;
  // Golden-section search for the maximum on [t_{best−1}, t_{best+1}].
  constexpr double kGolden = 0.6180339887498949;
  double lo = (best - 1.0) / intervals, hi = (best + 1.0) / intervals;
  double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
  double f1 = deviation_at(x1), f2 = deviation_at(x2);
  for (int it = 0; it < 20; ++it) {
    if (f1 > f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kGolden * (hi - lo);
      f1 = deviation_at(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kGolden * (hi - lo);
      f2 = deviation_at(x2);
    }
  }
  return signed_worst;
}

// The chord fields of the point that ends a segment, from its error as distribute()
// measures it (from the band's centre, the blocks' stand-off above the design).
inline void set_chord(ContactPoint& p, const AxisState& s, double error, bool jump,
                      double stand_off) {
  p.stand_off = stand_off;
  p.chord_error = stand_off + std::abs(error);
  p.chord_below = error < -stand_off;
  p.chord_jump = jump;
  p.uncut_residual = s.uncut;
}

// A jump: over a rejected step the programmed point moves this many times farther than the
// contact. Along a smooth offset it moves |1 + Rκ| times as far, a few at most; across a
// jump the ratio grows without bound as the step shrinks.
constexpr double kJumpRatio = 100;

// Walks τ from 0 to tau_end, calling emit(state, chord_error, jump) for every point, the
// chord error signed as segment_error's. `jump` marks a segment across which the
// programmed point jumps (the nose centre at a crease sharper than the nose: the offset
// of a concave crease is not the offset of either side): its error stops falling with the
// step, so the step search accepts a short step over it and reports the error as it is.
template <class Path, class Emit>
void distribute(Path& path, const CutterPointOptions& o, Emit&& emit) {
  const double end = path.tau_end();
  AxisState current, trial;
  path.at(0.0, current);
  path.commit(current);
  emit(current, 0.0, false);
  if (!(end > 0)) return;
  const double order = o.interpolation == Interpolation::kLinear ? 2.0 : 4.0;
  // The band is [0, ε] above the design, its centre the blocks' stand-off: each segment
  // may bend ε − stand_off either way from it (margin for the sampled maximum).
  const double target = 0.97 * (o.tolerance - path.stand_off());
  const double min_step = 1e-12 * std::max(1.0, end);
  double step = std::min(path.cap(), end);
  while (current.tau < end) {
    const double remaining = end - current.tau;
    // The end is reached exactly, never by a sum that rounds short of it.
    const auto advance = [&](double d) { return d >= remaining ? end : current.tau + d; };
    const double limit = std::min(path.cap(), remaining);
    double error = 0;
    bool jump = false;
    if (o.rule == CutterPointRule::kEqualAngle) {
      step = std::min(2 * std::numbers::pi / o.points_per_revolution, remaining);
      path.at(advance(step), trial);
      error = segment_error(path, current, trial, o.interpolation);
    } else if (o.rule == CutterPointRule::kEqualArcLength) {
      step = std::min(step, limit);
      for (int it = 0; it < 3; ++it) {
        path.at(advance(step), trial);
        const double chord = (trial.point - current.point).norm();
        const double next = chord > 0 ? std::min(limit, step * o.arc_length / chord) : limit;
        if (std::abs(next - step) <= 1e-3 * step) break;
        step = next;
      }
      path.at(advance(step), trial);
      error = segment_error(path, current, trial, o.interpolation);
    } else {
      // The largest step whose error is at most the target: e ∝ step^order locally, so
      // the secant-like update converges in a few evaluations.
      step = std::min(step, limit);
      double accepted = 0;
      AxisState best;
      double best_error = 0;
      // The last rejected step: across a crease (a lenslet's rim) the error stops falling
      // with the step while the chord still spans the crease, so the local order is
      // measured and a step that barely helps is halved instead.
      double failed_step = 0, failed_error = 0;
      for (int it = 0; it < 80; ++it) {
        path.at(advance(step), trial);
        const double signed_error = segment_error(path, current, trial, o.interpolation);
        error = std::abs(signed_error);
        double next;
        if (error <= target) {
          if (step > accepted) {
            accepted = step;
            best = trial;
            best_error = signed_error;
          }
          if (step >= limit || error >= 0.9 * target) break;
          next = error > 0 ? step * std::min(2.0, std::pow(target / error, 1 / order) * 0.995)
                           : 2 * step;
          next = std::min(next, limit);
        } else {
          double local_order = order;
          if (failed_step > 0 && failed_step != step && failed_error > 0)
            local_order = std::log(failed_error / error) / std::log(failed_step / step);
          next = local_order < 0.5
                     ? 0.5 * step
                     : step * std::max(0.2, 0.99 * std::pow(target / error,
                                                            1 / std::min(local_order, order)));
          failed_step = step;
          failed_error = error;
          const double contact_move = (trial.point - current.point).norm();
          const double axes_move =
              std::hypot(trial.x_axis - current.x_axis, trial.z - current.z,
                         0.5 * (std::abs(trial.x_axis) + std::abs(current.x_axis)) * (trial.c - current.c));
          if (axes_move > kJumpRatio * contact_move) {
            // This step crosses the jump. A shorter accepted one would only end before it,
            // and the next search would close in on it without end.
            accepted = step;
            best = trial;
            best_error = signed_error;
            jump = true;
            break;
          }
          if (accepted > 0 && next <= accepted) break;  // nothing between them is better
        }
        if (next < min_step)
          throw InputError("θ = " + std::to_string(current.c) + " rad, r = " +
                               std::to_string(current.contact_r) + " mm",
                           "cannot meet the chord tolerance " + std::to_string(o.tolerance * 1e3) +
                               " µm: the path is not smooth here");
        if (std::abs(next - step) <= 1e-6 * step && accepted > 0) break;
        step = next;
      }
      if (accepted == 0)
        throw InputError("θ = " + std::to_string(current.c) + " rad, r = " +
                             std::to_string(current.contact_r) + " mm",
                         "no step meets the chord tolerance " + std::to_string(o.tolerance * 1e3) +
                             " µm");
      trial = best;
      error = best_error;
      step = accepted;
    }
    // A last sliver shorter than a millionth of a step joins this one instead.
    if (end - trial.tau < 1e-6 * step && trial.tau < end) {
      path.at(end, trial);
      error = segment_error(path, current, trial, o.interpolation);
    }
    path.commit(trial);
    current = trial;
    emit(current, error, jump);
  }
}

}  // namespace freeturn::detail
