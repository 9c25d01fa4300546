#pragma once
// XY polynomial ("Extended Polynomial"): a conic plus Σ A_i x^a y^b / R_n^{a+b}, terms
// ordered x, y, x², xy, y², x³, …; for x^a y^b with n = a + b the 1-based index is
// i = (n−1)(n+2)/2 + b + 1 (x²y² is term 12). Up to 230 terms (order 20).

#include <array>
#include <vector>

#include "freeturn/surface/conic.hpp"
#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

struct Monomial {
  int a = 0, b = 0;  // powers of x and y
};

// The monomial of 1-based term index i (1 ≤ i ≤ 230).
Monomial xy_polynomial_term(int index);

class XyPolynomial final : public JetSurface<XyPolynomial> {
 public:
  // coefficients[i − 1] is A_i; normalization_radius R_n > 0.
  XyPolynomial(double curvature, double conic, double normalization_radius,
               const std::vector<double>& coefficients);
  const char* type() const override { return "xy_polynomial"; }
  double defined_radius() const override { return conic_defined_radius(c_, k_); }
  // The conic's largest eigenvalue within `radius` plus a bound of the terms' bend there
  // (surface/bend_bounds.hpp).
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T r2 = x * x + y * y;
    T z = conic_sag(c_, k_, r2);
    // Powers of x/R_n and y/R_n up to the highest order, then each term's product.
    T px[kMaxOrder + 1], py[kMaxOrder + 1];
    px[0] = py[0] = T(1.0);
    const T xn = x / rn_, yn = y / rn_;
    for (int k = 1; k <= order_; ++k) {
      px[k] = px[k - 1] * xn;
      py[k] = py[k - 1] * yn;
    }
    for (const Term& t : terms_) z += t.coefficient * (px[t.a] * py[t.b]);
    return z;
  }

 private:
  static constexpr int kMaxOrder = 20;
  struct Term {
    int a, b;
    double coefficient;
  };
  double c_, k_, rn_;
  int order_ = 0;
  std::vector<Term> terms_;  // the non-zero ones
  std::array<double, kMaxOrder + 1> abs_by_order_{};  // Σ |coefficient| of each order (max_bend)
};

}  // namespace freeturn
