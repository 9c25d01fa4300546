#include "freeturn/surface/polynomial_height.hpp"

#include "freeturn/core/error.hpp"
#include "freeturn/surface/zernike.hpp"

namespace freeturn {

PolynomialHeight::PolynomialHeight(double normalization_radius, int degree,
                                   std::vector<double> coefficients)
    : r_(normalization_radius), degree_(degree), c_(std::move(coefficients)) {
  if (!(r_ > 0)) throw InputError("normalization_radius", "must be greater than 0");
  if (degree_ < 0 || c_.size() != static_cast<std::size_t>((degree_ + 1) * (degree_ + 1)))
    throw InputError("coefficients", "a polynomial of degree d has (d + 1)² coefficients");
}

PolynomialHeight PolynomialHeight::from_zernike(double normalization_radius,
                                                const std::vector<double>& a) {
  int degree = 0;
  std::vector<double> c = zernike_power_coefficients(a, degree);
  return PolynomialHeight(normalization_radius, degree, std::move(c));
}

void PolynomialHeight::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  const double X = x / r_, Y = y / r_;
  const int w = degree_ + 1;
  // q_b(X) = Σ_a c_ab X^a and q_b'(X) by Horner, then the same in Y.
  z = zx = zy = 0;
  for (int b = degree_; b >= 0; --b) {
    double q = 0, dq = 0;
    for (int a = degree_ - b; a >= 0; --a) {
      dq = dq * X + q;
      q = q * X + c_[static_cast<std::size_t>(a * w + b)];
    }
    zy = zy * Y + z;
    z = z * Y + q;
    zx = zx * Y + dq;
  }
  zx /= r_;
  zy /= r_;
}

HeightDerivatives PolynomialHeight::height_derivatives(double x, double y) const {
  const double X = x / r_, Y = y / r_;
  const int w = degree_ + 1;
  HeightDerivatives h;
  for (int b = degree_; b >= 0; --b) {
    double q = 0, dq = 0, ddq = 0;
    for (int a = degree_ - b; a >= 0; --a) {
      ddq = ddq * X + 2 * dq;
      dq = dq * X + q;
      q = q * X + c_[static_cast<std::size_t>(a * w + b)];
    }
    // Horner in Y for p(Y) = Σ q_b Y^b and its Y derivatives, with the X derivatives'
    // polynomials alongside.
    h.zyy = h.zyy * Y + 2 * h.zy;
    h.zy = h.zy * Y + h.z;
    h.z = h.z * Y + q;
    h.zxy = h.zxy * Y + h.zx;
    h.zx = h.zx * Y + dq;
    h.zxx = h.zxx * Y + ddq;
  }
  const double s = 1 / r_;
  h.zx *= s;
  h.zy *= s;
  h.zxx *= s * s;
  h.zxy *= s * s;
  h.zyy *= s * s;
  return h;
}

}  // namespace freeturn
