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
  // The tool whose programmed point the machine moves (cutter_points.hpp): the chord
  // error is measured on that motion; tool.nose_radius also gives the scallop.
  ToolMotion tool;
  CutterPointOptions points;  // kEqualArcLength or kChordError; max_radial_step caps a step
};

// Contact points with θ = 0 (x = r, y = 0) from r = outer to r = inner. Throws InputError
// for a surface that is not rotationally symmetric (naming r, θ and the deviation) and
// for equal-angle points, which need a spiral.
PathSummary plan_profile(const Surface& design, const ProfileOptions& options, ContactSink& sink);

}  // namespace freeturn
