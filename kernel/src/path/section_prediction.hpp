#pragma once
// Per-point prediction shared by the planners: the surface's radial section at a contact
// point, the pass spacing along it, and the scallop the tool's nose leaves.

#include <algorithm>
#include <cmath>

#include "freeturn/path/contact_point.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::detail {

// Fills normal and section_curvature of `p` (point and θ set) from the design surface.
// The section is the surface's curve in the radial plane at θ; its curvature is the
// normal curvature along T = (e_r + z_r e_z)/√(1 + z_r²):
//   κ = e_rᵀ ∇²z e_r / ((1 + z_r²) √(1 + |∇z|²)), > 0 concave as seen from the tool.
// Returns z_r, the radial slope.
//
// radial_slope (optional): the slope the tool sees in the radial plane where it is not the
// design's, over a ridge the nose rolls over (section_envelope.hpp): the normal then takes
// it in place of the design's radial slope, so that compensation puts the centre where
// the planner placed it; the tangential slope stays the design's.
// at_ridge: the touch lies on a ridge (NoseTouch::at_ridge). The section bends away from
// the nose at that corner, so no flank's concavity is the touch's: the curvature is taken
// as at most 0 there. A bowl tighter than the nose, whose rims the nose rests on, had
// failed the local gouge check on its own rims' touches.
inline double fill_section(const Surface& design, ContactPoint& p,
                           const double* radial_slope = nullptr, bool at_ridge = false) {
  const HeightDerivatives h = design.height_derivatives(p.point.x(), p.point.y());
  const double c = std::cos(p.theta), s = std::sin(p.theta);
  p.normal = Eigen::Vector3d(-h.zx, -h.zy, 1).normalized();
  const double zr = h.zx * c + h.zy * s;
  if (radial_slope) {
    const double zt = -h.zx * s + h.zy * c;
    p.normal = Eigen::Vector3d(-(*radial_slope * c - zt * s), -(*radial_slope * s + zt * c), 1)
                   .normalized();
  }
  const double zrr = h.zxx * c * c + 2 * h.zxy * c * s + h.zyy * s * s;
  p.section_curvature =
      zrr / ((1 + zr * zr) * std::sqrt(1 + h.zx * h.zx + h.zy * h.zy));
  if (at_ridge) p.section_curvature = std::min(p.section_curvature, 0.0);
  return radial_slope ? *radial_slope : zr;
}

// Scallop height between passes f apart on a section of curvature κ cut by a nose of
// radius R: the sagitta of a circle of the relative radius R_e = 1/(1/R − κ) over the
// chord f, R_e − √(R_e² − f²/4) ≈ (f²/8)(1/R − κ): exact on a flat (κ = 0), where the
// parabolic form falls short by f⁴/128R³ (0.4 nm of 625 at R 0.5 mm, f 50 µm), enough to
// stop it bounding the simulated cut. 0 without a nose radius.
inline double scallop_height(double spacing, double curvature, double nose_radius) {
  if (!(nose_radius > 0)) return 0.0;
  const double relative = 1 / nose_radius - curvature;
  if (!(relative > 0)) return 0.0;
  const double r_e = 1 / relative, half = 0.5 * spacing;
  if (half >= r_e) return spacing * spacing / 8 * relative;  // the passes do not overlap as circles
  return r_e - std::sqrt(r_e * r_e - half * half);
}

}  // namespace freeturn::detail
