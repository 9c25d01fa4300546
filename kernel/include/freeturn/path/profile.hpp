#pragma once
// Profile mode: a two-axis X-Z path for a rotationally symmetric part, along the profile
// z(r) = f(r, 0) from the aperture's edge to its centre (the spindle turns continuously;
// C is not programmed). The design surface is first checked for rotational symmetry.

#include "freeturn/path/contact_point.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct ProfileOptions {
  double outer_radius = 0, inner_radius = 0;  // mm
  // Refuse a surface whose sag varies around the axis by more than this (mm).
  double symmetry_tolerance = 1e-6;
  // The tool's nose radius (mm): the chord error is measured on the nose-centre motion
  // the machine interpolates (0: on the contact path).
  double nose_radius = 0;
  // Where the programmed point sits relative to the nose centre, and whether B follows
  // (ToolMotion; its nose_radius is this nose_radius).
  double axis_offset = 0;
  bool b_follows = false;
  double edge_angle = 0;  // rad
  CutterPointOptions points;  // kEqualArcLength or kChordError; max_radial_step caps a step
};

// Contact points with θ = 0 (x = r, y = 0) from r = outer to r = inner. Throws InputError
// for a surface that is not rotationally symmetric (naming r, θ and the deviation) and
// for equal-angle points, which need a spiral.
PathSummary plan_profile(const Surface& design, const ProfileOptions& options, ContactSink& sink);

}  // namespace freeturn
