#include "freeturn/surface/xy_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/surface/bend_bounds.hpp"

namespace freeturn {

Monomial xy_polynomial_term(int index) {
  if (index < 1 || index > 230)
    throw InputError("term " + std::to_string(index), "XY polynomial terms are numbered 1 to 230");
  // Terms of total order n occupy indices (n−1)(n+2)/2 + 1 … (n−1)(n+2)/2 + n + 1.
  int n = 1;
  while ((n) * (n + 3) / 2 < index) ++n;
  const int b = index - (n - 1) * (n + 2) / 2 - 1;
  return {n - b, b};
}

XyPolynomial::XyPolynomial(double curvature, double conic, double normalization_radius,
                           const std::vector<double>& coefficients)
    : c_(curvature), k_(conic), rn_(normalization_radius) {
  if (!(rn_ > 0)) throw InputError("normalization_radius", "must be greater than 0");
  if (coefficients.size() > 230)
    throw InputError("coefficients", "at most 230 XY polynomial terms");
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    if (coefficients[i] == 0) continue;
    const Monomial m = xy_polynomial_term(static_cast<int>(i) + 1);
    terms_.push_back({m.a, m.b, coefficients[i]});
    order_ = std::max(order_, m.a + m.b);
    abs_by_order_[static_cast<std::size_t>(m.a + m.b)] += std::abs(coefficients[i]);
  }
}

double XyPolynomial::max_bend(double radius) const {
  return conic_max_bend(c_, k_, radius) + power_terms_max_bend(abs_by_order_, rn_, radius);
}

double XyPolynomial::max_slope(double radius) const {
  return conic_max_slope(c_, k_, radius) + power_terms_max_slope(abs_by_order_, rn_, radius);
}

}  // namespace freeturn
