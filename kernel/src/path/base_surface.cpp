#include "freeturn/path/base_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/gauss_legendre.hpp"
#include "freeturn/nurbs/knot_vector.hpp"

namespace freeturn {
namespace {

// The generating curve as (ρ, H(ρ), 0) with parameter u = ρ: the ρ coordinates of the
// control points are the Greville abscissae, which reproduce ρ exactly.
nurbs::NurbsCurve generating_curve(int degree, const std::vector<double>& knots,
                                   const std::vector<double>& coefficients) {
  const std::size_t n = coefficients.size();
  if (knots.size() != n + static_cast<std::size_t>(degree) + 1)
    throw InputError("base surface", "a degree-" + std::to_string(degree) + " curve with " +
                                         std::to_string(n) + " coefficients needs " +
                                         std::to_string(n + degree + 1) + " knots, not " +
                                         std::to_string(knots.size()));
  const nurbs::KnotVector knot_vector(degree, knots);
  std::vector<nurbs::Vector3d> points;
  for (std::size_t i = 0; i < n; ++i)
    points.emplace_back(knot_vector.greville(static_cast<int>(i)), coefficients[i], 0.0);
  return nurbs::NurbsCurve(degree, knots, points);
}

}  // namespace

BaseSurface BaseSurface::plane(double rho_max) {
  BaseSurface b(1, {0, 0, rho_max, rho_max}, {0, 0});
  b.plane_ = true;
  return b;
}

BaseSurface::BaseSurface(int degree, std::vector<double> knots, std::vector<double> coefficients)
    : degree_(degree),
      knots_(std::move(knots)),
      coefficients_(std::move(coefficients)),
      rho_max_(knots_.empty() ? 0.0 : knots_.back()),
      table_(generating_curve(degree_, knots_, coefficients_)) {
  if (!(knots_.front() == 0.0 && rho_max_ > 0))
    throw InputError("base surface", "the generating curve must run from ρ = 0 to ρ_max > 0");
  // Each non-empty knot span [t_k, t_{k+1}) as the Taylor coefficients H^(m)(t_k)/m! of its
  // polynomial, from the curve's derivatives there (A3.2 and A4.2): from_parameter.
  const nurbs::NurbsCurve& curve = table_.curve();
  std::vector<nurbs::Vector3d> d(static_cast<std::size_t>(degree_) + 1);
  for (std::size_t k = static_cast<std::size_t>(degree_); k + 1 < knots_.size(); ++k) {
    if (!(knots_[k + 1] > knots_[k])) continue;
    span_start_.push_back(knots_[k]);
    curve.derivatives(knots_[k], degree_, d.data());
    double factorial = 1;
    for (int m = 0; m <= degree_; ++m) {
      if (m > 0) factorial *= m;
      span_taylor_.push_back(d[static_cast<std::size_t>(m)].y() / factorial);
    }
  }
  build_inverse_table();
}

void BaseSurface::build_inverse_table() {
  const double total = table_.total();
  const int n = static_cast<int>(std::clamp(total / 0.002, 1024.0, 65536.0));
  ds_ = total / n;
  inverse_rho_.resize(static_cast<std::size_t>(n) + 1);
  inverse_d1_.resize(inverse_rho_.size());
  inverse_d2_.resize(inverse_rho_.size());
  // March along the curve: ρ_k solves s(ρ_k) = k·ds by Newton, with s(ρ) − s(ρ_{k−1}) from
  // an 8-point Gauss–Legendre rule over the short step (a smooth integrand there, error
  // far below 1e-15 mm), started from the Taylor step ds·ρ' + ds²ρ''/2.
  const nurbs::QuadratureRule rule = nurbs::gauss_legendre(8);
  const auto speed = [&](double rho) {
    const double slope = from_parameter(rho).slope;
    return std::sqrt(1 + slope * slope);
  };
  const auto length = [&](double a, double b) {
    double sum = 0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i)
      sum += rule.weights[i] * speed(0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[i]);
    return 0.5 * (b - a) * sum;
  };
  const auto store = [&](int k, double rho) {
    const BasePoint b = from_parameter(rho);
    const double q = 1 + b.slope * b.slope;
    inverse_rho_[static_cast<std::size_t>(k)] = rho;
    inverse_d1_[static_cast<std::size_t>(k)] = 1 / std::sqrt(q);
    inverse_d2_[static_cast<std::size_t>(k)] = -b.slope * b.curvature / (q * q);
  };
  store(0, 0.0);
  double rho = 0, s = 0;  // the last node and its exact arc length
  for (int k = 1; k <= n; ++k) {
    const std::size_t a = static_cast<std::size_t>(k - 1);
    double next = std::min(rho_max_, rho + ds_ * inverse_d1_[a] + 0.5 * ds_ * ds_ * inverse_d2_[a]);
    if (k == n) {
      next = rho_max_;
    } else {
      for (int it = 0; it < 8; ++it) {
        const double step = (s + length(rho, next) - k * ds_) / speed(next);
        next = std::clamp(next - step, rho, rho_max_);
        if (std::abs(step) <= 1e-15 * rho_max_) break;
      }
    }
    s += length(rho, next);
    rho = next;
    store(k, rho);
  }
}

BasePoint BaseSurface::from_parameter(double u) const {
  if (plane_) return {u, 0.0, 0.0, 0.0};
  // x(u) = u, so H, dH/dρ and d²H/dρ² are the scalar spline's value and derivatives: on
  // span k a polynomial in h = ρ − t_k, by Horner's rule from its Taylor coefficients at
  // t_k (taken from the curve at construction). The spiral evaluates the base at every
  // point it tries, and the rational curve's A3.2 with A2.3 (its divisions) cost a tenth of
  // the planner on the compound eye.
  const int p = degree_;
  u = std::clamp(u, 0.0, rho_max_);
  const std::size_t k = static_cast<std::size_t>(
      std::upper_bound(span_start_.begin() + 1, span_start_.end(), u) - span_start_.begin() - 1);
  const double h = u - span_start_[k];
  const double* a = &span_taylor_[k * static_cast<std::size_t>(p + 1)];
  BasePoint b{u, a[p], 0.0, 0.0};
  for (int m = p - 1; m >= 0; --m) b.h = b.h * h + a[m];
  b.slope = p * a[p];
  for (int m = p - 1; m >= 1; --m) b.slope = b.slope * h + m * a[m];
  if (p >= 2) {
    b.curvature = p * (p - 1) * a[p];
    for (int m = p - 1; m >= 2; --m) b.curvature = b.curvature * h + m * (m - 1) * a[m];
  }
  return b;
}

BasePoint BaseSurface::at_radius(double rho) const {
  return from_parameter(rho);  // clamped there
}

BasePoint BaseSurface::at_arc_length(double s) const {
  if (plane_) return {std::clamp(s, 0.0, rho_max_), 0.0, 0.0, 0.0};
  const int n = static_cast<int>(inverse_rho_.size()) - 1;
  if (s <= 0) return from_parameter(0.0);
  if (s >= ds_ * n) {
    // Past its edge the generating curve goes on along its tangent: the spiral's first
    // contact may need a few µm more of base than the aperture (path/spiral.cpp).
    BasePoint p = from_parameter(rho_max_);
    const double beyond = s - ds_ * n, c = 1 / std::sqrt(1 + p.slope * p.slope);
    p.rho += beyond * c;
    p.h += beyond * c * p.slope;
    p.curvature = 0;
    return p;
  }
  const int k = std::min(n - 1, static_cast<int>(s / ds_));
  const double t = s / ds_ - k, h = ds_;
  const std::size_t a = static_cast<std::size_t>(k), b = a + 1;
  // Quintic Hermite basis on [0, 1].
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  const double h0 = 1 - 10 * t3 + 15 * t4 - 6 * t5, h1 = t - 6 * t3 + 8 * t4 - 3 * t5,
               h2 = 0.5 * (t2 - 3 * t3 + 3 * t4 - t5), h3 = 0.5 * (t3 - 2 * t4 + t5),
               h4 = -4 * t3 + 7 * t4 - 3 * t5, h5 = 10 * t3 - 15 * t4 + 6 * t5;
  const double rho = h0 * inverse_rho_[a] + h1 * h * inverse_d1_[a] +
                     h2 * h * h * inverse_d2_[a] + h3 * h * h * inverse_d2_[b] +
                     h4 * h * inverse_d1_[b] + h5 * inverse_rho_[b];
  return from_parameter(rho);
}

double BaseSurface::arc_length(double rho) const {
  if (plane_) return std::clamp(rho, 0.0, rho_max_);
  return table_.length_to(std::clamp(rho, 0.0, rho_max_));
}

Eigen::Vector3d BaseSurface::point(const BasePoint& b, const RadialLine& line) {
  return {b.rho * line.cos, b.rho * line.sin, b.h};
}

Eigen::Vector3d BaseSurface::normal(const BasePoint& b, const RadialLine& line) {
  const double k = 1.0 / std::sqrt(1.0 + b.slope * b.slope);
  return {-b.slope * line.cos * k, -b.slope * line.sin * k, k};
}

}  // namespace freeturn
