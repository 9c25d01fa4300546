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

#include "freeturn/path/cutter_points.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

class NoseSection {
 public:
  // stand_off: how far the programmed nose stands off the design along the section normal
  // (half the chord tolerance: cutter_points.hpp, "one-sided band").
  NoseSection(const Surface& design, const ToolMotion& motion, double stand_off)
      : design_(design), R_(motion.nose_radius), stand_off_(stand_off),
        offset_(motion.b_follows ? motion.axis_offset : 0.0), b_follows_(motion.b_follows),
        edge_angle_(motion.edge_angle) {}

  double nose_radius() const { return R_; }
  double stand_off() const { return stand_off_; }
  bool b_follows() const { return b_follows_; }

  // The axes of the point that touches the design at signed radius contact_r in the radial
  // plane, height z, with section slope f_r = dz/dρ: the centre c = p + R·n̂_p, n̂_p the
  // section normal (−f_r, 1)/√(1 + f_r²) (as compensate() places it, tool/compensation).
  // B (rad) is ψ − edge_angle when it follows, else 0 (a fixed B drops out).
  void axes(double contact_r, double z, double f_r, double& x_axis, double& z_axis,
            double& b) const {
    b = b_follows_ ? std::atan2(-f_r, 1.0) - edge_angle_ : 0.0;
    const double offset = R_ + stand_off_;
    if (offset == 0) {
      x_axis = contact_r;
      z_axis = z;
    } else {
      const double length = std::sqrt(1 + f_r * f_r);
      x_axis = contact_r - offset * f_r / length;
      z_axis = z + offset / length;
    }
    x_axis += offset_ * std::sin(b);
    z_axis += offset_ * std::cos(b);
  }

  // Where the nose touches for the contact (contact_r, z) with section slope f_r at angle
  // c: the contact itself, or, where the nose would overhang a crease, the touch on the
  // contact's flank of the nose held at that crease (path/section_envelope.hpp). With B
  // following the normal the nose is not held (its edge point is fixed, not its centre).
  NoseTouch touch(double c, double contact_r, double z, double f_r) const {
    if (R_ == 0 || b_follows_) {
      NoseTouch t;
      t.rho = contact_r;
      t.z = z;
      t.slope = f_r;
      return t;
    }
    return nose_touch(design_, c, R_, contact_r, z, f_r, stand_off_);
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
    // The largest height of the design's section above the nose's lower arc, from a
    // Newton search at the hint and at each crease under the nose (section_envelope.hpp):
    // a value of the overlap, so never more than the true one, and short of it by a
    // fourth-order term on a smooth piece.
    const NoseOverlap o = nose_overlap(design_, c, x_axis, z_axis, R_, hint_r);
    return -o.height / std::sqrt(1 + o.slope * o.slope);
  }

 private:
  const Surface& design_;
  double R_, stand_off_, offset_;
  bool b_follows_;
  double edge_angle_;
};

}  // namespace freeturn::detail
