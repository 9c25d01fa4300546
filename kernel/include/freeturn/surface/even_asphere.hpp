#pragma once
// Even asphere: conic plus even polynomial in r (shared/notes/optical-surfaces.md),
//   z = c r² / (1 + √(1 − (1+k) c² r²)) + Σ_{i=2..10} A_{2i} r^{2i}.
// A sphere is k = 0, a paraboloid k = −1, a plane c = 0 and no coefficients.

#include <array>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class EvenAsphere final : public Surface {
 public:
  // curvature: c = 1/R_vertex in 1/mm (R > 0 puts the centre of curvature at +z).
  // conic: k. coefficients: A4, A6, …, A20 (mm^(1−2i)); missing ones are zero.
  EvenAsphere(double curvature, double conic, const std::array<double, 9>& coefficients = {});

  const char* type() const override { return "even_asphere"; }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;

  // Largest radius at which the conic's square root stays real (infinity if none).
  double defined_radius() const override;
  // The conic's largest eigenvalue within `radius` plus a bound of the terms' bend there
  // (surface/bend_bounds.hpp).
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;

  double curvature() const { return c_; }
  double conic() const { return k_; }

 private:
  // z = F(s) with s = r²; F and its first two derivatives in s (the second only where
  // kSecond: the planner's sag_gradient asks for F and F' alone). Working in s keeps the
  // formulas free of the 1/r that a derivation in r has at the vertex.
  template <bool kSecond>
  void sag_in_s(double s, double& f, double& df, double& d2f) const;

  double c_, k_;
  std::array<double, 9> a_;  // A4 … A20
};

}  // namespace freeturn
