#pragma once
// Zernike Standard Sag (shared/notes/optical-surfaces.md): a conic plus even-asphere terms
// plus Σ A_j Z_j(ρ, φ), ρ = r / R_norm, Noll ordering and normalisation, up to 231 terms:
//   Z_j = N_n^m R_n^|m|(ρ) · {cos(mφ) for m ≥ 0 … sin(|m|φ) for m < 0},
//   N = √(n+1) for m = 0, √(2(n+1)) otherwise.
// Written without φ: ρ^|m| {cos, sin}(|m|φ) = {Re, Im}((X + iY)^|m|) with X = x/R, Y = y/R,
// and R_n^|m|(ρ) = (−1)^k ρ^|m| P_k^(|m|,0)(1 − 2ρ²), k = (n − |m|)/2, a Jacobi polynomial
// evaluated by its three-term recurrence (Abramowitz & Stegun 22.7.1): the power-basis
// coefficients reach 1.8e5 at n = 20 and would lose five digits to cancellation. Every
// term is a polynomial in x and y, smooth at the vertex.

#include <array>
#include <vector>

#include "freeturn/surface/conic.hpp"
#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

struct ZernikeIndex {
  int n = 0, m = 0;  // radial order, signed azimuthal frequency (m < 0: sine)
};

// (n, m) of Noll index j, 1 ≤ j ≤ 231.
ZernikeIndex noll_to_nm(int j);

// Z_j at (ρ, φ), straight from the definition with trigonometric functions: the
// reference the tests compare the polynomial form with.
double zernike_polar(int j, double rho, double phi);

// Σ a_j Z_j as a polynomial in the normalised X = x/R_n, Y = y/R_n, expanded exactly:
// ρ^{n−2k} {cos, sin}(|m|φ) = (X² + Y²)^{(n−2k−|m|)/2} {Re, Im}((X + iY)^|m|). Returns the
// coefficient of X^a Y^b at [a·(degree + 1) + b] and sets `degree` (the largest n). For
// the low orders a measured error is fitted with (n ≤ 10) the coefficients stay small;
// at n = 20 they reach 1e5 and the Jacobi form (Zernike) is the one to use.
std::vector<double> zernike_power_coefficients(const std::vector<double>& a, int& degree);

class Zernike final : public JetSurface<Zernike> {
 public:
  // coefficients[j − 1] is A_j (mm); asphere: A4 … A20 on r⁴ … r²⁰ as in EvenAsphere.
  Zernike(double curvature, double conic, const std::array<double, 9>& asphere,
          double normalization_radius, const std::vector<double>& coefficients);
  const char* type() const override { return "zernike"; }
  double defined_radius() const override { return conic_defined_radius(c_, k_); }
  // The conic's largest eigenvalue within `radius` plus bounds of the asphere terms' and the
  // Zernike terms' bend there, the latter from their expansion in powers of x and y
  // (surface/bend_bounds.hpp; loose at high orders, where the powers' coefficients cancel).
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T r2 = x * x + y * y;
    T z = conic_sag(c_, k_, r2);
    T p = T(0.0);
    for (int i = 8; i >= 0; --i) p = p * r2 + asphere_[i];
    z += p * r2 * r2;
    if (orders_.empty()) return z;
    // Powers of the complex number X + iY, and s = X² + Y².
    const T xn = x / rn_, yn = y / rn_;
    T re[kMaxM + 1], im[kMaxM + 1];
    re[0] = T(1.0);
    im[0] = T(0.0);
    for (int k = 1; k <= max_m_; ++k) {
      re[k] = re[k - 1] * xn - im[k - 1] * yn;
      im[k] = re[k - 1] * yn + im[k - 1] * xn;
    }
    const T u = 1.0 - 2.0 * (xn * xn + yn * yn);  // the Jacobi argument 1 − 2ρ²
    // One recurrence per azimuthal order |m| serves every term of that order: the
    // cosine and sine coefficients of each degree k are summed as it goes.
    for (const Order& o : orders_) {
      const double a = o.m;
      T previous = T(1.0), current = T(1.0);
      T sum_cos = o.cos_coefficient[0] * current, sum_sin = o.sin_coefficient[0] * current;
      for (int q = 1; q <= o.k_max; ++q) {
        T next;
        if (q == 1) {
          next = 0.5 * ((a + 2) * u + a);
        } else {
          const double c1 = 2.0 * q * (q + a) * (2 * q + a - 2);
          const double c2 = (2 * q + a - 1) * (2 * q + a) * (2 * q + a - 2);
          const double c3 = (2 * q + a - 1) * a * a;
          const double c4 = 2.0 * (q + a - 1) * (q - 1) * (2 * q + a);
          next = ((c2 / c1) * u + c3 / c1) * current - (c4 / c1) * previous;
        }
        previous = current;
        current = next;
        sum_cos += o.cos_coefficient[q] * current;
        sum_sin += o.sin_coefficient[q] * current;
      }
      z += sum_cos * re[o.m] + sum_sin * im[o.m];
    }
    return z;
  }

 private:
  static constexpr int kMaxM = 20;
  // All terms of one azimuthal order |m|: coefficient (A_j · N · (−1)^k) of the Jacobi
  // polynomial of degree k = (n − |m|)/2, for the cosine (m ≥ 0) and sine (m < 0) parts.
  struct Order {
    int m = 0;
    int k_max = 0;
    std::array<double, 11> cos_coefficient{}, sin_coefficient{};
  };
  double c_, k_, rn_;
  std::array<double, 9> asphere_;
  int max_m_ = 0;
  std::vector<Order> orders_;
  std::vector<double> abs_by_order_;  // Σ |power coefficient| of each order n (max_bend)
};

}  // namespace freeturn
