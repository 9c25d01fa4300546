#pragma once
// z = Σ c_ab X^a Y^b with X = x/R, Y = y/R: a height polynomial evaluated by nested Horner
// schemes (in X for every power of Y, then in Y), value and derivatives together. The form
// a fitted error is cut with (metrology): a sum of Zernike terms expanded once
// (zernike_power_coefficients) costs a few multiply-adds a term where the Jacobi form
// costs recurrences through jets.

#include <vector>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class PolynomialHeight final : public Surface {
 public:
  // coefficients[a·(degree + 1) + b] multiplies X^a Y^b (entries with a + b > degree are 0).
  PolynomialHeight(double normalization_radius, int degree, std::vector<double> coefficients);
  // Σ a_j Z_j(x/R_n, y/R_n) (Noll), expanded.
  static PolynomialHeight from_zernike(double normalization_radius, const std::vector<double>& a);

  const char* type() const override { return "polynomial"; }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;

 private:
  double r_;
  int degree_;
  std::vector<double> c_;
};

}  // namespace freeturn
