#pragma once
// Forbes Q-bfs asphere (G. W. Forbes, "Shape specification for axially symmetric optical
// surfaces", Opt. Express 15, 5218 (2007), Eq. 2.2-2.3):
//   z = c r² / (1 + √(1 − c² r²)) + u²(1 − u²)/√(1 − c² r²) · Σ_{m=0..M} a_m Q_m(u²),
// with u = r / r_max and c the curvature of the best-fit sphere. The departure is
// measured along the sphere's normal and the Q_m are orthonormal in slope, so a_m are
// the r.m.s. slope contributions of each term. Q_m by the three-term recurrence of
// Forbes's Appendix A (f_m, g_m, h_m), evaluated in x = u² on jets.

#include <array>
#include <vector>

#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

class Qbfs final : public JetSurface<Qbfs> {
 public:
  // curvature: of the best-fit sphere (1/mm); normalization_radius r_max (mm, > 0);
  // coefficients a_0 … a_M (mm), M ≤ 30.
  Qbfs(double curvature, double normalization_radius, std::vector<double> coefficients);

  const char* type() const override { return "qbfs"; }
  double defined_radius() const override;
  double max_bend(double radius) const override;
  double max_slope(double radius) const override;

  // Q_m(x) for m = 0 … count−1 (the polynomials themselves, for tests).
  static std::vector<double> polynomials(double x, int count);

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T s = x * x + y * y;
    const T q = sqrt(1.0 - c_ * c_ * s);
    const T sphere = c_ * s / (1.0 + q);
    if (a_.empty()) return sphere;
    const T w = s * inv_r2_;  // u²
    return sphere + w * (1.0 - w) / q * series(w);
  }

 private:
  // Σ a_m Q_m(w): Q_m = (P_m − g_{m−1} Q_{m−1} − h_{m−2} Q_{m−2}) / f_m with
  // P_0 = 2, P_1 = 6 − 8w, P_m = (2 − 4w) P_{m−1} − P_{m−2}.
  template <typename T>
  T series(const T& w) const {
    const T t = 2.0 - 4.0 * w;
    T p_prev = T(2.0), p = 6.0 - 8.0 * w;  // P_0, P_1
    T q_prev2 = T(0.0), q_prev = T(1.0);  // Q_{−1} (unused), Q_0
    T sum = a_[0] * q_prev;
    if (a_.size() == 1) return sum;
    T q = (p - g_[0] * q_prev) / f_[1];
    sum += a_[1] * q;
    for (std::size_t m = 2; m < a_.size(); ++m) {
      const T p_next = t * p - p_prev;
      p_prev = p;
      p = p_next;
      q_prev2 = q_prev;
      q_prev = q;
      q = (p - g_[m - 1] * q_prev - h_[m - 2] * q_prev2) / f_[m];
      sum += a_[m] * q;
    }
    return sum;
  }

  // Bounds of |S|, |S'| and |S''| over w ∈ [0, w_max] (w_max ≥ 1), S(w) = Σ a_m Q_m(w)
  // (max_bend).
  std::array<double, 3> series_bounds(double w_max) const;
  // Bounds of the departure's |dD/ds| and |d²D/ds²| within the radius; false where the
  // best-fit sphere does not reach it.
  bool departure_bounds(double radius, double& d1, double& d2) const;

  // f_m, g_m, h_m for m < n (Forbes 2007, Appendix A).
  static void recurrence(std::size_t n, std::vector<double>& f, std::vector<double>& g,
                         std::vector<double>& h);

  double c_, inv_r2_;
  std::vector<double> a_;
  std::vector<double> f_, g_, h_;  // recurrence coefficients
  std::array<double, 3> unit_series_bounds_{};  // series_bounds(1): within r_max
};

}  // namespace freeturn
