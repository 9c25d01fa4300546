#include "freeturn/surface/even_asphere.hpp"

#include "freeturn/surface/bend_bounds.hpp"
#include "freeturn/surface/conic.hpp"

#include <cmath>
#include <limits>

namespace freeturn {

EvenAsphere::EvenAsphere(double curvature, double conic, const std::array<double, 9>& coefficients)
    : c_(curvature), k_(conic), a_(coefficients) {}

double EvenAsphere::defined_radius() const {
  return conic_defined_radius(c_, k_);
}

double EvenAsphere::max_bend(double radius) const {
  return conic_max_bend(c_, k_, radius) + even_terms_max_bend(a_, radius);
}

double EvenAsphere::max_slope(double radius) const {
  return conic_max_slope(c_, k_, radius) + even_terms_max_slope(a_, radius);
}

template <bool kSecond>
void EvenAsphere::sag_in_s(double s, double& f, double& df, double& d2f) const {
  // Conic: with q = √(1 − (1+k)c²s), F = c s/(1+q), F' = c/(2q), F'' = (1+k)c³/(4q³).
  // The form c s/(1+q) avoids the cancellation of (1 − q)/((1+k)c) near the vertex.
  const double q = std::sqrt(1.0 - (1.0 + k_) * c_ * c_ * s);
  f = c_ * s / (1.0 + q);
  df = c_ / (2.0 * q);
  if constexpr (kSecond) d2f = (1.0 + k_) * c_ * c_ * c_ / (4.0 * q * q * q);
  // Polynomial Σ A_{2i} s^i, i = 2..10, by Horner with its two derivatives.
  double p = 0, dp = 0, d2p = 0;
  for (int i = 10; i >= 2; --i) {
    if constexpr (kSecond) d2p = d2p * s + 2.0 * dp;
    dp = dp * s + p;
    p = p * s + a_[static_cast<std::size_t>(i - 2)];
  }
  // Horner above evaluated P(s)/s² with P = Σ A s^i; restore the s² factor.
  const double s2 = s * s;
  f += p * s2;
  df += dp * s2 + 2.0 * s * p;
  if constexpr (kSecond) d2f += d2p * s2 + 4.0 * s * dp + 2.0 * p;
}

void EvenAsphere::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  double f, df, unused;
  sag_in_s<false>(x * x + y * y, f, df, unused);
  z = f;
  zx = 2.0 * x * df;
  zy = 2.0 * y * df;
}

HeightDerivatives EvenAsphere::height_derivatives(double x, double y) const {
  double f, df, d2f;
  sag_in_s<true>(x * x + y * y, f, df, d2f);
  HeightDerivatives h;
  h.z = f;
  h.zx = 2.0 * x * df;
  h.zy = 2.0 * y * df;
  h.zxx = 2.0 * df + 4.0 * x * x * d2f;
  h.zxy = 4.0 * x * y * d2f;
  h.zyy = 2.0 * df + 4.0 * y * y * d2f;
  return h;
}

}  // namespace freeturn
