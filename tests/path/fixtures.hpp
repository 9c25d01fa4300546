#pragma once
// Shapes shared by the path tests.

#include <cmath>
#include <span>
#include <vector>

#include "freeturn/nurbs/surface.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"

namespace freeturn::test {

// A surface that counts the evaluations of its heights asked of it (values and gradients,
// or with Hessians), and passes every question on to `inner`.
class CountingSurface final : public Surface {
 public:
  explicit CountingSurface(const Surface& inner) : inner_(inner) {}
  const char* type() const override { return inner_.type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    ++evaluations;
    inner_.sag_gradient(x, y, z, zx, zy);
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    ++evaluations;
    return inner_.height_derivatives(x, y);
  }
  double defined_radius() const override { return inner_.defined_radius(); }
  bool has_creases() const override { return inner_.has_creases(); }
  int section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                      std::span<double> out) const override {
    return inner_.section_creases(line, rho_lo, rho_hi, out);
  }
  double max_bend(double radius) const override { return inner_.max_bend(radius); }
  int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const override {
    return inner_.creases_near(x, y, radius, out);
  }
  mutable long evaluations = 0;

 private:
  const Surface& inner_;
};

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
