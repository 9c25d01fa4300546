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

class Zernike final : public JetSurface<Zernike> {
 public:
  // coefficients[j − 1] is A_j (mm); asphere: A4 … A20 on r⁴ … r²⁰ as in EvenAsphere.
  Zernike(double curvature, double conic, const std::array<double, 9>& asphere,
          double normalization_radius, const std::vector<double>& coefficients);
  const char* type() const override { return "zernike"; }
  double defined_radius() const override;

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T r2 = x * x + y * y;
    T z = c_ * r2 / (1.0 + sqrt(1.0 - (1 + k_) * c_ * c_ * r2));
    T p = T(0.0);
    for (int i = 8; i >= 0; --i) p = p * r2 + asphere_[i];
    z += p * r2 * r2;
    if (terms_.empty()) return z;
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
    for (const Term& t : terms_) {
      const int am = t.m < 0 ? -t.m : t.m;
      const double a = am;
      T previous = T(1.0), current = T(1.0);
      if (t.k >= 1) current = 0.5 * ((a + 2) * u + a);
      for (int q = 2; q <= t.k; ++q) {
        const double c1 = 2.0 * q * (q + a) * (2 * q + a - 2);
        const double c2 = (2 * q + a - 1) * (2 * q + a) * (2 * q + a - 2);
        const double c3 = (2 * q + a - 1) * a * a;
        const double c4 = 2.0 * (q + a - 1) * (q - 1) * (2 * q + a);
        const T next = ((c2 * u + c3) * current - c4 * previous) / c1;
        previous = current;
        current = next;
      }
      z += t.coefficient * (current * (t.m < 0 ? im[am] : re[am]));
    }
    return z;
  }

 private:
  static constexpr int kMaxM = 20;
  struct Term {
    int m;               // signed azimuthal frequency
    int k;               // Jacobi degree (n − |m|)/2
    double coefficient;  // A_j · N · (−1)^k
  };
  double c_, k_, rn_;
  std::array<double, 9> asphere_;
  int max_m_ = 0;
  std::vector<Term> terms_;
};

}  // namespace freeturn
