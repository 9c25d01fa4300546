#include "freeturn/surface/xy_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"

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
  }
}

double XyPolynomial::max_bend(double radius) const {
  double bend = conic_max_bend(c_, k_, radius);
  // A term A (x/R_n)^a (y/R_n)^b, n = a + b, along a unit direction u: its second derivative
  // is A/R_nⁿ (a(a−1)x^{a−2}y^b u_x² + 2ab x^{a−1}y^{b−1}u_x u_y + b(b−1)x^a y^{b−2}u_y²),
  // at most |A|/R_nⁿ · n(n−1) r^{n−2} where |x|, |y| ≤ r: the bracket is at most a(a−1) for
  // b = 0, and (a|u_x| + b|u_y|)² − a u_x² − b u_y² ≤ a² + b² − min(a, b) ≤ n(n−1) otherwise.
  for (const Term& t : terms_) {
    const int n = t.a + t.b;
    if (n < 2) continue;
    bend += std::abs(t.coefficient) * n * (n - 1) * std::pow(radius / rn_, n - 2) / (rn_ * rn_);
  }
  return bend;
}

}  // namespace freeturn
