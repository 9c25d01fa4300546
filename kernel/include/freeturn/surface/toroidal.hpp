#pragma once
// Toroidal (shared/notes/optical-surfaces.md): a YZ profile
//   z_y(y) = c y² / (1 + √(1 − (1+k) c² y²)) + Σ_{i=1..8} α_i y^{2i}
// rotated about an axis parallel to y at distance R_rot:
//   z = R_rot − sgn(R_rot)·√((R_rot − z_y)² − x²);   R_rot = 0 is a cylinder, z = z_y.

#include <array>

#include "freeturn/surface/conic.hpp"
#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

class Toroidal final : public JetSurface<Toroidal> {
 public:
  // alpha: α_1 … α_8 on y², y⁴, …, y¹⁶.
  Toroidal(double curvature, double conic, double rotation_radius,
           const std::array<double, 8>& alpha)
      : c_(curvature), k_(conic), r_(rotation_radius), alpha_(alpha) {}
  const char* type() const override { return "toroidal"; }
  double max_bend(double radius) const override;

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T y2 = y * y;
    T zy = conic_sag(c_, k_, y2);
    T power = y2;
    for (double a : alpha_) {
      zy += a * power;
      power = power * y2;
    }
    if (r_ == 0) return zy;
    const T d = r_ - zy;
    return r_ - (r_ > 0 ? 1.0 : -1.0) * sqrt(d * d - x * x);
  }

 private:
  double c_, k_, r_;
  std::array<double, 8> alpha_;
};

}  // namespace freeturn
