#pragma once
// A design sample seen from a candidate axis of revolution, with derivatives in the axis
// parameters by forward-mode automatic differentiation (Eigen's AutoDiffScalar). Shared by
// the least-squares and minimax base fits. Internal to the path module.
//
// Axis: direction t = R_y(tilt_y) R_x(tilt_x) e_z, through (shift_x, shift_y, 0). For a
// sample point P with unit normal n: d = P − o, h = d·t, w = d − h t, ρ = |w|, and n's
// components along t, e_ρ = w/ρ and e_θ = t × e_ρ. With the base slope H'(ρ), the base
// normal is (t − H' e_ρ)/√(1 + H'²) and the meridian tangent (e_ρ + H' t)/√(1 + H'²), so
//   cos α = (n_h − n_ρ H')/√(1 + H'²),   sin²α = r² + n_θ²,   r = (n_ρ + n_h H')/√(1 + H'²).

#include <algorithm>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/knot_vector.hpp"
#include "freeturn/path/base_surface_fit.hpp"

namespace freeturn::detail {

using AxisAd = Eigen::AutoDiffScalar<Eigen::Vector4d>;

struct RevolutionTerms {
  AxisAd rho, n_h, n_rho, n_theta;
};

// axis: [tilt_x, tilt_y, shift_x, shift_y], or null for the z axis (derivatives zero).
inline RevolutionTerms revolution_terms(const SurfaceSample& s, const double* axis) {
  const Eigen::Vector3d& n = s.normal;
  RevolutionTerms out;
  const Eigen::Vector4d zero = Eigen::Vector4d::Zero();
  if (axis == nullptr) {
    const double r = s.point.head<2>().norm();
    out.rho = AxisAd(r, zero);
    out.n_h = AxisAd(n.z(), zero);
    out.n_rho = AxisAd(r > 1e-9 ? n.head<2>().dot(s.point.head<2>()) / r : 0.0, zero);
    out.n_theta = AxisAd(r > 1e-9 ? (s.point.x() * n.y() - s.point.y() * n.x()) / r : 0.0, zero);
    return out;
  }
  const AxisAd tx(axis[0], 4, 0), ty(axis[1], 4, 1), ox(axis[2], 4, 2), oy(axis[3], 4, 3);
  const AxisAd t0 = cos(tx) * sin(ty), t1 = -sin(tx), t2 = cos(tx) * cos(ty);
  const AxisAd d0 = s.point.x() - ox, d1 = s.point.y() - oy;
  const double d2 = s.point.z();
  const AxisAd h = d0 * t0 + d1 * t1 + d2 * t2;
  const AxisAd w0 = d0 - h * t0, w1 = d1 - h * t1, w2 = d2 - h * t2;
  const AxisAd rho2 = w0 * w0 + w1 * w1 + w2 * w2;
  out.n_h = n.x() * t0 + n.y() * t1 + n.z() * t2;
  // On the axis ρ is not differentiable; H'(0) = 0 and the azimuth is undefined there,
  // so the sample only contributes n_h.
  if (rho2.value() > 1e-18) {
    out.rho = sqrt(rho2);
    out.n_rho = (n.x() * w0 + n.y() * w1 + n.z() * w2) / out.rho;
    // e_θ = t × e_ρ.
    const AxisAd e0 = (t1 * w2 - t2 * w1) / out.rho, e1 = (t2 * w0 - t0 * w2) / out.rho,
                 e2 = (t0 * w1 - t1 * w0) / out.rho;
    out.n_theta = n.x() * e0 + n.y() * e1 + n.z() * e2;
  } else {
    out.rho = AxisAd(0.0, zero);
    out.n_rho = AxisAd(0.0, zero);
    out.n_theta = AxisAd(0.0, zero);
  }
  return out;
}

// H'(ρ) and H''(ρ) of the base with coefficients c (c_0 = c_1 = 0 implied when
// `free_from_two`: the array holds c_2 … c_{n−1}), and the first derivatives of the
// p + 1 basis functions that are non-zero at ρ (index span − p + j).
class BaseSlope {
 public:
  BaseSlope(int degree, const std::vector<double>& knots)
      : degree_(degree), knots_(knots), kv_(degree, knots),
        ders_(static_cast<std::size_t>(3 * (degree + 1))),
        work_(nurbs::basis_derivatives_work_size(degree)) {}

  // Evaluates at ρ (clamped to the domain) with the free coefficients c_2 … .
  void evaluate(double rho, const double* free_coefficients) {
    const double r = std::clamp(rho, knots_.front(), knots_.back());
    span_ = kv_.find_span(r);
    nurbs::basis_function_derivatives(span_, r, degree_, 2, knots_.data(), ders_.data(),
                                      work_.data());
    const int q = degree_ + 1;
    slope = curvature = 0;
    for (int j = 0; j < q; ++j) {
      const int i = first() + j;
      const double c = i <= 1 ? 0.0 : free_coefficients[i - 2];
      slope += c * ders_[static_cast<std::size_t>(q + j)];
      curvature += c * ders_[static_cast<std::size_t>(2 * q + j)];
    }
  }
  int first() const { return span_ - degree_; }
  int count() const { return degree_ + 1; }
  // dH'/dc_{first + j}.
  double basis_slope(int j) const { return ders_[static_cast<std::size_t>(degree_ + 1 + j)]; }

  double slope = 0, curvature = 0;

 private:
  int degree_;
  std::vector<double> knots_;
  nurbs::KnotVector kv_;
  std::vector<double> ders_, work_;
  int span_ = 0;
};

}  // namespace freeturn::detail
