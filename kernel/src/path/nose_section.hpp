#pragma once
// The motion the machine interpolates is the programmed point's, not the contact's: with
// a nose of radius R the nose centre rides R above the design along the section normal,
// and its path curves differently from the contact path (on an off-axis sphere, by tens
// of times at coarse steps). The chord error is therefore measured as the gap between the
// interpolated nose's lower arc and the design's radial section. Internal to the path
// module (spiral.cpp, profile.cpp, path_stepper.hpp).
//
// With R = 0 the axes are the contact's and the gap is its distance from the design.
// With a fixed B axis every program point (nose centre, tip, pivot) is the centre plus a
// constant, so linear or cubic interpolation of any of them moves the centre the same way.
// With B following the normal, the pivot (or tip) and B are interpolated, and the centre
// swings on an arc about the pivot: the axes carry the programmed point and B, and the
// centre is recovered from them at every sample.

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeturn/path/cutter_points.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

class NoseSection {
 public:
  NoseSection(const Surface& design, const ToolMotion& motion)
      : design_(design), R_(motion.nose_radius),
        offset_(motion.b_follows ? motion.axis_offset : 0.0), b_follows_(motion.b_follows),
        edge_angle_(motion.edge_angle) {}

  double nose_radius() const { return R_; }
  bool b_follows() const { return b_follows_; }

  // The axes of the point that touches the design at signed radius contact_r in the radial
  // plane at angle c, height z, with sag gradient (fx, fy): the centre c = p + R·n̂_p, n̂_p
  // the section normal (−f_r, 1)/√(1 + f_r²) (as compensate() places it, tool/compensation).
  // B (rad) is ψ − edge_angle when it follows, else 0 (a fixed B drops out).
  void axes(double contact_r, double c, double z, double fx, double fy, double& x_axis,
            double& z_axis, double& b) const {
    const double f_r = fx * std::cos(c) + fy * std::sin(c);
    b = b_follows_ ? std::atan2(-f_r, 1.0) - edge_angle_ : 0.0;
    if (R_ == 0) {
      x_axis = contact_r;
      z_axis = z;
    } else {
      const double length = std::sqrt(1 + f_r * f_r);
      x_axis = contact_r - R_ * f_r / length;
      z_axis = z + R_ / length;
    }
    x_axis += offset_ * std::sin(b);
    z_axis += offset_ * std::cos(b);
  }

  // The distance (mm, along the design normal) between the design and the tool placed at
  // the axes (x_axis, c, z_axis), signed: > 0 where the tool passes above the design
  // (material left), < 0 where it cuts into it. hint_r: the contact's radius nearby (the interpolated
  // one), where the gap is smallest.
  double deviation(double x_axis, double c, double z_axis, double b, double hint_r) const {
    x_axis -= offset_ * std::sin(b);
    z_axis -= offset_ * std::cos(b);
    const double ct = std::cos(c), st = std::sin(c);
    double f, fx, fy;
    if (R_ == 0) {
      design_.sag_gradient(x_axis * ct, x_axis * st, f, fx, fy);
      return (z_axis - f) / std::sqrt(1 + fx * fx + fy * fy);
    }
    // The nose's lower arc is z_c − s(r), s = √(R² − (r − x_c)²). Where the tool clears the
    // design, g(r) = f(r) − (z_c − s) is ≤ 0; its largest value is the gap (< 0: material
    // left) or the overlap (> 0: a cut into the design). g' = f_r − (r − x_c)/s and
    // g'' = f_rr − R²/s³. One Newton step from the hint, with the arc's −R²/s³ for g''
    // (f_rr unknown), and the larger g of the two points: a value of g, so never more
    // than its maximum, and short of it by ½|g''|δr², δr the step's miss, which is
    // f_rr/(f_rr − R²/s³) of the hint's: small unless the design curves like the nose.
    const double reach = 0.999 * R_;
    double best = -std::numeric_limits<double>::infinity(), slope_sq = 0;
    double r = hint_r;
    for (int it = 0; it < 2; ++it) {
      design_.sag_gradient(r * ct, r * st, f, fx, fy);
      const double d = std::clamp(r - x_axis, -reach, reach);
      const double s = std::sqrt(R_ * R_ - d * d);
      const double g = f - z_axis + s;
      if (g > best) {
        best = g;
        slope_sq = fx * fx + fy * fy;
      }
      const double gp = (fx * ct + fy * st) - d / s;
      r = std::clamp(r + gp * s * s * s / (R_ * R_), x_axis - reach, x_axis + reach);
    }
    return -best / std::sqrt(1 + slope_sq);
  }

 private:
  const Surface& design_;
  double R_, offset_;
  bool b_follows_;
  double edge_angle_;
};

}  // namespace freeturn::detail
