#pragma once
// Nose-radius compensation by the sectional curve method (paper 002, Fig. 2-6), and the
// B axis of 4-axis turning (paper 000, §5).
//
// In the radial plane at θ (coordinates (ρ, z), e_r = (cos θ, sin θ, 0)) the contact p
// has the in-plane normal n̂_p = (n·e_r, n_z)/|·| at angle ψ = atan2(n·e_r, n_z) from +z.
// The tool axis a(B) = (sin B, cos B) points from the nose centre toward the holder; the
// edge touches at ψ − B from it. The nose centre is
//   c = p + (R + δ(ψ − B)) n̂_p         (δ: the measured waviness),
// which keeps c in the radial plane: offsetting along the full 3D normal would move it to
// another angle. The programmed point is c (nose centre), c − R a(B) (the tip), or, with
// a B axis, its pivot c + L a(B). With the edge's centre height h above the spindle line
// the edge is an arc in the rake plane (machine y = h), not in a radial plane: the spindle
// stands at C = θ − β, sin β = h/ρ, which brings the contact p (radius ρ) into that plane
// √(ρ² − h²) along e = (cos C, sin C, 0), and the section above takes e for e_r. The nose
// then touches the design tangentially in the plane it cuts in (docs/tool.md).

#include <cmath>

#include "freeturn/path/cutter_points.hpp"
#include "freeturn/surface/surface.hpp"
#include "freeturn/tool/cutter_location.hpp"
#include "freeturn/tool/tool_geometry.hpp"

namespace freeturn {

enum class BMode {
  kFixed,   // B stays at `b_fixed` (3-axis machines: 0)
  kFollow,  // B = ψ − edge_angle: the edge touches at `edge_angle` from the tool axis
};

struct CompensationOptions {
  ToolGeometry tool;
  BMode b_mode = BMode::kFixed;
  double b_fixed = 0;     // rad
  double edge_angle = 0;  // rad, the nose point that touches when B follows (0: its centre)
  double pivot_distance = 0;  // L (mm): B pivot to nose centre; 0: program the nose point
};

// The programmed point's offset from the nose centre along the tool axis a(B): the pivot
// distance L with a B pivot, −R for the tip, 0 for the nose centre. The one rule for it:
// compensation, its inverse, the planner's motion and the clearance base all use it.
double programmed_point_offset(const CompensationOptions& options);

// What the machine's axes carry, for the planner's chord error (path/cutter_points.hpp).
ToolMotion tool_motion(const CompensationOptions& options);

// Whether the edge, `centre_height` off the spindle line, reaches the signed radius `rho`
// of the contact's radial line: it reaches no radius under |h|. Where it does not,
// compensate() leaves X undefined (NaN) and the centre check reports it.
inline bool edge_reaches(double rho, double centre_height) {
  return centre_height == 0 || std::abs(rho) >= std::abs(centre_height);
}

// The cutter location for one contact point. No checks (tool_checks.hpp); no allocation.
CutterLocation compensate(const ContactPoint& contact, const CompensationOptions& options);
// The same, given the radial line at contact.theta (RadialLine(contact.theta), the same
// bits): the stage after the planner computes it once a point for this and the checks.
CutterLocation compensate(const ContactPoint& contact, const CompensationOptions& options,
                          const RadialLine& line);

// The inverse for tests and verification: from programmed axes (x, z, B) back to the nose
// centre's distance from the spindle axis (signed as x) and height — x, z being the point
// `options` programs.
Eigen::Vector2d nose_centre_from_axes(double x, double z, double b,
                                      const CompensationOptions& options);
// The angle on the part (rad) of the nose centre programmed at spindle angle c (rad), x
// and B: c itself, turned by atan2(h, c_x) when the edge sits h above the spindle line,
// c_x the centre's machine x.
double work_angle_from_axes(double c, double x, double b, const CompensationOptions& options);

}  // namespace freeturn
