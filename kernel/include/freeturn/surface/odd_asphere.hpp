#pragma once
// Odd asphere: a conic plus a polynomial in every power of r (Zemax "Odd Asphere";
// shared/notes/optical-surfaces.md),
//   z = c r² / (1 + √(1 − (1+k) c² r²)) + Σ_{i=1..N} β_i r^i.
// The odd powers are not smooth at the vertex: β₁ r is a cone (no gradient at r = 0; the
// value reported there is 0, its average over directions) and β₃ r³ has a Hessian that is
// continuous but not differentiable there.

#include <vector>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class OddAsphere final : public Surface {
 public:
  // curvature c = 1/R (1/mm); conic k; coefficients β₁ … β_N (mm^(1−i)), N ≤ 30.
  OddAsphere(double curvature, double conic, std::vector<double> coefficients);

  const char* type() const override { return "odd_asphere"; }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;
  double defined_radius() const override;
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;
  double max_section_bend(double radius) const override;
  bool has_creases() const override { return !beta_.empty() && beta_[0] != 0; }

 private:
  // The radial profile z(r) as: z, g1 = z'(r)/r and g2 = (z'' − z'/r)/r², so that
  // ∇z = g1·(x, y) and the Hessian is g1·I + g2·(x, y)(x, y)ᵀ, without 1/r at the vertex.
  void radial(double x, double y, double& z, double& g1, double& g2) const;

  double c_, k_;
  std::vector<double> beta_;  // β₁ … β_N
};

}  // namespace freeturn
