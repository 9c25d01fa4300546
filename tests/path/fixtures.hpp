#pragma once
// Shapes shared by the path tests.

#include <cmath>
#include <vector>

#include "freeturn/nurbs/surface.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"

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

// A rational bicubic `count` × `count` net over [−6, 6]² whose x and y are perturbed, so
// that the height field must invert (x, y) → (u, v) (warm-started from the thread's last
// answer), with smooth bumps of ±`amplitude` mm.
inline NurbsHeightField wavy_nurbs(int count, double amplitude) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights, knots = {0, 0, 0, 0};
  for (int k = 1; k < count - 3; ++k) knots.push_back(static_cast<double>(k) / (count - 3));
  knots.insert(knots.end(), {1, 1, 1, 1});
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j) {
      const double x = -6 + 12.0 * i / (count - 1) + 0.05 * std::sin(j),
                   y = -6 + 12.0 * j / (count - 1) + 0.05 * std::cos(i);
      points.emplace_back(x, y, amplitude * std::sin(x / 3) * std::cos(y / 4));
      weights.push_back(1 + 0.1 * std::sin(i + j));
    }
  return NurbsHeightField(nurbs::NurbsSurface(3, 3, knots, knots, points, weights));
}

}  // namespace freeturn::test
