#include "freeturn/path/base_surface_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/knot_vector.hpp"
#include "revolution_terms.hpp"

namespace freeturn {

std::vector<SurfaceSample> sample_aperture(const Surface& surface, double inner_radius,
                                           double outer_radius, int radial, int angular) {
  std::vector<SurfaceSample> out;
  out.reserve(static_cast<std::size_t>(radial * angular));
  for (int i = 0; i < radial; ++i) {
    const double r = inner_radius + (outer_radius - inner_radius) * i / (radial - 1);
    const int count = r == 0 ? 1 : angular;
    for (int j = 0; j < count; ++j) {
      const double phi = 2 * std::numbers::pi * j / angular;
      const double x = r * std::cos(phi), y = r * std::sin(phi);
      double z, zx, zy;
      surface.sag_gradient(x, y, z, zx, zy);
      if (!(std::isfinite(z) && std::isfinite(zx) && std::isfinite(zy)))
        throw InputError("(x, y) = (" + std::to_string(x) + ", " + std::to_string(y) + ") mm",
                         "the design surface is undefined inside the aperture",
                         "aperture.outer_radius");
      out.push_back({{x, y, z}, Eigen::Vector3d(-zx, -zy, 1).normalized()});
    }
  }
  return out;
}

BaseSurface fit_base_least_squares(const std::vector<SurfaceSample>& samples,
                                   const BaseFitOptions& options) {
  double rho_max = options.rho_max;
  if (rho_max <= 0)
    for (const SurfaceSample& s : samples) rho_max = std::max(rho_max, s.point.head<2>().norm());
  if (!(rho_max > 0)) throw InputError("base surface", "the samples do not leave the axis");
  const int p = options.degree, spans = options.spans, n = spans + p;
  std::vector<double> knots(static_cast<std::size_t>(p), 0.0);
  for (int k = 0; k <= spans; ++k) knots.push_back(rho_max * k / spans);
  knots.insert(knots.end(), static_cast<std::size_t>(p), rho_max);
  const nurbs::KnotVector kv(p, knots);

  // Unknowns: c_0 (= c_1, which makes H'(0) = 0) and c_2 … c_{n−1}.
  const int m = n - 1;
  const auto unknown = [](int i) { return i <= 1 ? 0 : i - 1; };
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  std::vector<double> basis(static_cast<std::size_t>(p + 1));
  for (const SurfaceSample& s : samples) {
    const double rho = std::min(s.point.head<2>().norm(), rho_max);
    const int span = kv.find_span(rho);
    nurbs::basis_functions(span, rho, p, knots.data(), basis.data());
    for (int j = 0; j <= p; ++j) {
      const int uj = unknown(span - p + j);
      b(uj) += basis[static_cast<std::size_t>(j)] * s.point.z();
      for (int k = 0; k <= p; ++k)
        a(uj, unknown(span - p + k)) += basis[static_cast<std::size_t>(j)] * basis[static_cast<std::size_t>(k)];
    }
  }
  // Second differences of the coefficients, weighted far below the data.
  const double weight = 1e-9 * std::max(1.0, a.trace() / m);
  for (int i = 0; i + 2 < n; ++i) {
    const int idx[3] = {unknown(i), unknown(i + 1), unknown(i + 2)};
    const double w[3] = {1, -2, 1};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) a(idx[j], idx[k]) += weight * w[j] * w[k];
  }
  const Eigen::VectorXd c = a.ldlt().solve(b);
  std::vector<double> coefficients(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) coefficients[static_cast<std::size_t>(i)] = c(unknown(i));
  return BaseSurface(p, knots, coefficients);
}

QuasiRevolution measure_quasi_revolution(const std::vector<SurfaceSample>& samples,
                                         const BaseSurface& base, const BaseAxis& axis) {
  // The design normal's components along the base normal (cos α), the meridian tangent
  // (r) and around the axis (n_θ): sin α = |(r, n_θ)| (revolution_terms.hpp).
  const double a[4] = {axis.tilt_x, axis.tilt_y, axis.shift_x, axis.shift_y};
  QuasiRevolution q;
  double sum = 0;
  for (const SurfaceSample& s : samples) {
    const detail::RevolutionTerms t = detail::revolution_terms(s, a);
    const BasePoint b = base.at_radius(t.rho.value());
    const double norm = std::sqrt(1 + b.slope * b.slope);
    const double cosine = (t.n_h.value() - t.n_rho.value() * b.slope) / norm;
    const double r = (t.n_rho.value() + t.n_h.value() * b.slope) / norm;
    const double angle = std::atan2(std::hypot(r, t.n_theta.value()), std::abs(cosine));
    sum += angle * angle;
    if (angle > q.max_angle) {
      q.max_angle = angle;
      q.where = s.point;
    }
  }
  q.rms_angle = samples.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(samples.size()));
  return q;
}

}  // namespace freeturn
