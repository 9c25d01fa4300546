#pragma once
// Shapes shared by the path tests.

#include "freeturn/surface/lenslet_array.hpp"

namespace freeturn::test {

// A compound eye: lenslets of R 5 mm (convex), D 0.9 mm, pitch 1 mm, in rings on a
// sphere of R 20 mm, out to `extent`.
inline LensletArrayOptions compound_eye_options(double extent) {
  LensletArrayOptions o;
  o.base_curvature = 1 / 20.0;
  o.lens_radius = -5.0;
  o.lens_diameter = 0.9;
  o.pitch = 1.0;
  o.pattern = LensletArrayOptions::Pattern::kRings;
  o.extent = extent;
  return o;
}

}  // namespace freeturn::test
