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
#include <string>

#include "freeturn/core/number_text.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/path/section_envelope.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

// Why the nose's envelope is not followed at signed radius r: the section meets more
// creases under the nose than a crease list holds (path/section_envelope.hpp).
inline std::string too_many_creases_under_nose(double r) {
  return "the section meets more than " + std::to_string(SectionCreases::kCapacity) +
         " creases of the design under the nose near r = " + fixed_text(std::abs(r), 4) +
         " mm, more than its envelope follows (use a nose radius that spans fewer of them)";
}

class NoseSection {
 public:
  // stand_off: how far the programmed nose stands off the design along the section normal
  // (half the chord tolerance: cutter_points.hpp, "one-sided band").
  NoseSection(const Surface& design, const ToolMotion& motion, double stand_off)
      : design_(design),
        R_(motion.nose_radius),
        stand_off_(stand_off),
        offset_(motion.b_follows ? motion.axis_offset : 0.0),
        b_follows_(motion.b_follows),
        edge_angle_(motion.edge_angle),
        floor_(motion.nose_radius > 0 ? edge_reach(motion, design) : 0.0) {}

  double nose_radius() const { return R_; }
  double stand_off() const { return stand_off_; }
  // How far above the design the motion must stay: what the real edge may reach past the
  // round nose (cutter_points.hpp, edge_reach), 0 for a round nose on the spindle line.
  double chord_floor() const { return floor_; }
  // How far the programmed point lies from the nose centre along B (a pivot's distance,
  // −R for the tip) where B follows the normal; 0 otherwise (a fixed B drops out).
  double axis_offset() const { return offset_; }
  bool b_follows() const { return b_follows_; }

  // Where the design's section curves toward the tool more tightly than the nose (its
  // curvature g''/(1 + g'²)^{3/2} above 1/R, the local gouge) anywhere under a nose touching
  // at contact_r on the line c, the text that says so, with the tightest radius among 65
  // samples across the nose's footprint and the nose's; "" where none does, or without a
  // nose. The chord search gives up there (no step follows such a section), and "not
  // smooth" alone did not tell the user that the nose is too large for the design.
  std::string nose_larger_than_section(const RadialLine& c, double contact_r) const {
    if (!(R_ > 0)) return "";
    double sharpest = 0, where = contact_r;
    for (int k = 0; k <= 64; ++k) {
      const double rho = contact_r + R_ * (k / 32.0 - 1);
      const HeightDerivatives h = design_.height_derivatives(rho * c.cos, rho * c.sin);
      const double slope = h.zx * c.cos + h.zy * c.sin;
      const double bend = (h.zxx * c.cos + 2 * h.zxy * c.sin) * c.cos + h.zyy * c.sin * c.sin;
      const double curvature = bend / std::pow(1 + slope * slope, 1.5);
      if (std::isfinite(curvature) && curvature > sharpest) sharpest = curvature, where = rho;
    }
    // The nose is placed at its radius plus the stand-off: a section between the two
    // radii is followed by no placement either.
    const double placed = R_ + stand_off_;
    if (!(sharpest * placed > 1)) return "";
    const std::string nose = sharpest * R_ > 1
                                 ? significant_text(R_, 6) + " mm"
                                 : significant_text(R_, 6) + " mm with its stand-off of " +
                                       significant_text(stand_off_ * 1e3, 3) + " µm";
    // A nose follows the section where its radius plus the stand-off stays under the
    // section's: where the stand-off alone reaches that radius no nose does, and the
    // radius to suggest would be 0 or negative.
    const double largest_nose = 1 / sharpest - stand_off_;
    const std::string instead =
        largest_nose > 0
            ? "use a nose radius under " + significant_text(largest_nose, 3) + " mm"
            : "no nose radius does: the stand-off of " + significant_text(stand_off_ * 1e3, 3) +
                  " µm alone is that radius or more, a section no nose can follow";
    return "the design's section bends to a concave radius of " +
           significant_text(1 / sharpest, 4) + " mm at r = " + fixed_text(std::abs(where), 4) +
           " mm, tighter than the nose radius " + nose + ": no nose position follows it (" +
           instead + ")";
  }

  // Where the nose, at its reach about the contact, spans more creases of the section than
  // a crease list holds (a lenslet array whose pitch is a small part of the nose): the
  // envelope makes no placement or measure from a list that is not whole, and takes the
  // nose to be in the design there (path/section_envelope.hpp). "" where it does not.
  std::string creases_past_the_list(const RadialLine& c, double contact_r) const {
    const double reach = R_ + stand_off_;
    if (!(reach > 0) || !design_.has_creases()) return "";
    SectionCreases creases;
    if (creases.find(design_, c, contact_r - 2 * reach, contact_r + 2 * reach)) return "";
    return too_many_creases_under_nose(contact_r);
  }

  // Why no step of a path through contact_r on the line c holds the chord tolerance, as far
  // as the nose can tell: a section tighter than the nose (above), or, with B following
  // the normal on a creased design, a valley: the nose is held at no crease then (one edge
  // point touches, and B turns with its normal), so where a crease is sharper than the nose
  // its offset overhangs the far flank. "" where neither explains it.
  std::string why_not_smooth(const RadialLine& c, double contact_r) const {
    std::string why = nose_larger_than_section(c, contact_r);
    if (why.empty()) why = creases_past_the_list(c, contact_r);
    // A fixed B rests the nose on both sides of a trough tighter than itself
    // (path/tight_troughs.hpp); a following one holds it nowhere.
    if (!why.empty() && b_follows_ && why.back() == ')')
      why.insert(why.size() - 1,
                 "; or cut it with b_axis: fixed, which rests the nose on both sides of such a "
                 "trough and leaves its bottom");
    if (why.empty() && b_follows_ && R_ > 0 && design_.has_creases())
      why = "with B following the normal the nose is held at no crease, and near r = " +
            fixed_text(std::abs(contact_r), 4) +
            " mm a valley of the design is sharper than the nose, whose offset would cut into "
            "the far flank (cut it with b_axis: fixed, which holds the nose in the valley)";
    return why;
  }

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
    if (offset_ != 0) {
      x_axis += offset_ * std::sin(b);
      z_axis += offset_ * std::cos(b);
    }
  }

  // Where the nose touches for the contact (contact_r, z) with section slope f_r at angle
  // c: the contact itself, or, where the nose would overhang a crease, the touch on the
  // contact's flank of the nose held at that crease, and over a ridge's window the nose
  // rolling over it (path/section_envelope.hpp). With B following the normal the nose is
  // not held (its edge point is fixed, not its centre), but it rolls.
  NoseTouch touch(const RadialLine& c, double contact_r, double z, double f_r) const {
    if (b_follows_ && R_ > 0) return nose_roll(design_, c, R_, contact_r, z, f_r, stand_off_);
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
  double deviation(double x_axis, const RadialLine& c, double z_axis, double b,
                   double hint_r) const {
    to_centre(x_axis, z_axis, b);
    if (R_ == 0) {
      double f, fx, fy;
      design_.sag_gradient(x_axis * c.cos, x_axis * c.sin, f, fx, fy);
      return (z_axis - f) / std::sqrt(1 + fx * fx + fy * fy);
    }
    // The largest height of the design's section above the nose's lower arc, from a
    // Newton search at the hint and at each crease under the nose (section_envelope.hpp):
    // a value of the overlap, so never more than the true one, and within 1 pm of it on a
    // smooth piece where the nose's concavity exceeds the design's (section_envelope.cpp).
    const NoseOverlap o = nose_overlap(design_, c, x_axis, z_axis, R_, hint_r);
    return -o.height / std::sqrt(1 + o.slope * o.slope);
  }

  // `deviation` searched from the hint alone, with no crease search, and where the nose
  // touches (touch_rho): the same value wherever touch_clear holds at that touch.
  double deviation_near_hint(double x_axis, const RadialLine& c, double z_axis, double b,
                             double hint_r, double& touch_rho) const {
    to_centre(x_axis, z_axis, b);
    const NoseOverlap o = nose_overlap_near(design_, c, x_axis, z_axis, R_, hint_r);
    touch_rho = o.rho;
    return -o.height / std::sqrt(1 + o.slope * o.slope);
  }

  // Whether a nose touching the design at signed radius rho on the radial line c, or
  // anywhere within `margin` of it, is clear of every crease (touch_clear_of_creases): not
  // held, and touching nowhere else. Measured with the placed nose's radius R + stand-off,
  // the larger. False without a nose, or with B following (no envelope is placed then).
  bool touch_clear(const RadialLine& c, double rho, double margin) const {
    if (R_ == 0 || b_follows_) return false;
    return touch_clear_of_creases(design_, rho * c.cos, rho * c.sin, R_ + stand_off_, margin);
  }

  // How far the nose at the axes (x_axis, z_axis, b) rises above the nose the path places
  // at the same τ (its axes ideal_x, ideal_z, ideal_b, touching the design at ideal_rho
  // with section slope ideal_slope), across the stretch of ±half_width about that touch
  // that this pass alone cuts (half the pass spacing; 0 for a single profile), along the
  // normal there. > 0: material left beyond what the path's own nose leaves.
  //
  // The gap `deviation` measures cannot see a nose that slides along the design: where the
  // path's nose jumps flank across a crease between two blocks, the interpolated one stays
  // in touch with the design but touches the wrong place, and the cusp between passes
  // grows with the slide (a 20 µm slide on a 0.2 mm nose leaves 1 µm). Two equal arcs
  // differ by a monotonic function of ρ, so its largest value lies at an end of the stretch.
  // `ends` (2, optional): the rise at each end, the slide their larger.
  double slide(double x_axis, double z_axis, double b, double ideal_x, double ideal_z,
               double ideal_b, double ideal_rho, double ideal_slope, double half_width,
               double* ends = nullptr) const {
    if (R_ == 0) {
      if (ends) ends[0] = ends[1] = 0.0;
      return 0.0;
    }
    to_centre(x_axis, z_axis, b);
    to_centre(ideal_x, ideal_z, ideal_b);
    const double R = R_ + stand_off_;  // the radius the centres are placed at
    const auto lower_arc = [R](double centre_x, double centre_z, double rho) {
      const double d = rho - centre_x;
      return centre_z - std::sqrt(std::max(R * R - d * d, 0.0));
    };
    const double normal = std::sqrt(1 + ideal_slope * ideal_slope);
    double rise = -1e300;
    for (int end = 0; end < 2; ++end) {
      const double rho = end == 0 ? ideal_rho - half_width : ideal_rho + half_width;
      const double here = lower_arc(x_axis, z_axis, rho) - lower_arc(ideal_x, ideal_z, rho);
      if (ends) ends[end] = here / normal;  // the division keeps the order: the same largest
      rise = std::max(rise, here);
    }
    return rise / normal;
  }

 private:
  // The nose centre from the axes (x, z, b): less the programmed point's offset from it,
  // which only a following B swings. Without one there is no offset, and its sine and
  // cosine (of B = 0, one pair per sample: a tenth of the planner's time on a compound
  // eye) are not taken; the centre is the same bits.
  void to_centre(double& x, double& z, double b) const {
    if (offset_ == 0) return;
    x -= offset_ * std::sin(b);
    z -= offset_ * std::cos(b);
  }

  const Surface& design_;
  double R_, stand_off_, offset_;
  bool b_follows_;
  double edge_angle_;
  double floor_;
};

}  // namespace freeturn::detail
