#include "freeturn/surface/xy_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
  if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
  // The conic z = c r²/(1 + √q), q = 1 − (1 + k)c²r², bends c/q^{3/2} along the radius and
  // c/√q along the circle. Where (1 + k) > 0, q falls with r: for c > 0 the larger, c/q^{3/2},
  // is largest at the rim of the disc, and for c < 0 both are at most c (at the axis). Where
  // (1 + k) ≤ 0, q ≥ 1 grows with r: for c > 0 both are at most c, and for c < 0 the larger,
  // c/q^{3/2}, is largest at the rim.
  const double q = 1 - (1 + k_) * c_ * c_ * radius * radius;
  if (!(q > 0)) return std::numeric_limits<double>::infinity();
  const double rim = c_ / (q * std::sqrt(q));
  double bend = (1 + k_ > 0) == (c_ > 0) ? rim : c_;
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
