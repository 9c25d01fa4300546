#include "freeturn/path/minimax_base_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "freeturn/core/minimax_sqp.hpp"
#include "freeturn/path/base_axis_fit.hpp"
#include "revolution_terms.hpp"

namespace freeturn {
namespace {

// Variables: c_2 … c_{n−1} (c_0 = c_1 = 0: the offset does not change a normal, and
// c_1 = c_0 keeps H'(0) = 0), then [tilt_x, tilt_y, shift_x, shift_y] when searching the
// axis. Functions: φ_k = 1 − cos α_k.
class RevolutionDeviation {
 public:
  RevolutionDeviation(const std::vector<SurfaceSample>& samples, const BaseSurface& start,
                      bool search_axis)
      : samples_(samples), search_axis_(search_axis), slope_(start.degree(), start.knots()),
        coefficients_(static_cast<int>(start.coefficients().size()) - 2) {}

  int variables() const { return coefficients_ + (search_axis_ ? 4 : 0); }

  Eigen::VectorXd variables_of(const BaseSurface& base, const BaseAxis& axis) const {
    Eigen::VectorXd x(variables());
    const std::vector<double>& c = base.coefficients();
    for (int i = 0; i < coefficients_; ++i) x(i) = c[static_cast<std::size_t>(i) + 2] - c[0];
    if (search_axis_) x.tail(4) << axis.tilt_x, axis.tilt_y, axis.shift_x, axis.shift_y;
    return x;
  }

  void operator()(const Eigen::VectorXd& x, Eigen::VectorXd& phi, Eigen::MatrixXd& gradients) {
    const std::size_t m = samples_.size();
    phi.resize(static_cast<Eigen::Index>(m));
    gradients.setZero(static_cast<Eigen::Index>(m), x.size());
    for (std::size_t k = 0; k < m; ++k) {
      const detail::RevolutionTerms t =
          detail::revolution_terms(samples_[k], search_axis_ ? x.data() + coefficients_ : nullptr);
      slope_.evaluate(t.rho.value(), x.data());
      const detail::AxisAd hp(slope_.slope, slope_.curvature * t.rho.derivatives());
      const detail::AxisAd cos_alpha = (t.n_h - t.n_rho * hp) / sqrt(1.0 + hp * hp);
      const Eigen::Index row = static_cast<Eigen::Index>(k);
      phi(row) = 1 - cos_alpha.value();
      const double h = hp.value();
      // ∂cos α/∂H' = (−n_ρ − n_h H')/(1 + H'²)^{3/2}.
      const double dcos_dslope = (-t.n_rho.value() - t.n_h.value() * h) / std::pow(1.0 + h * h, 1.5);
      for (int j = 0; j < slope_.count(); ++j) {
        const int i = slope_.first() + j;
        if (i >= 2) gradients(row, i - 2) -= dcos_dslope * slope_.basis_slope(j);
      }
      if (search_axis_)
        for (int a = 0; a < 4; ++a) gradients(row, coefficients_ + a) -= cos_alpha.derivatives()(a);
    }
  }

 private:
  const std::vector<SurfaceSample>& samples_;
  bool search_axis_;
  detail::BaseSlope slope_;
  int coefficients_;
};

}  // namespace

MinimaxBaseResult fit_base_minimax(const std::vector<SurfaceSample>& samples,
                                   const BaseSurface& start, const MinimaxBaseOptions& options) {
  MinimaxBaseResult result{start, {}};
  result.start_max_angle = measure_quasi_revolution(samples, start).max_angle;
  BaseSurface first = start;
  BaseAxis first_axis;
  result.least_squares_max_angle = result.start_max_angle;
  if (options.search_axis) {
    const BaseAxisFit lsq = fit_base_and_axis_least_squares(samples, start);
    first = lsq.base;
    first_axis = lsq.axis;
    result.least_squares_max_angle = lsq.max_angle;
    // A surface of revolution about some axis: the least-squares fit has found it, and no
    // maximum can be lower.
    if (lsq.max_angle < 1e-9) {
      result.base = lsq.base;
      result.axis = lsq.axis;
      result.max_angle = lsq.max_angle;
      result.status = lsq.status;
      return result;
    }
  }
  RevolutionDeviation deviation(samples, first, options.search_axis);
  const int n = deviation.variables();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(n, -kInf), upper = -lower;
  if (options.search_axis) {
    lower.tail(4) << -options.max_tilt, -options.max_tilt, -options.max_shift, -options.max_shift;
    upper.tail(4) = -lower.tail(4);
  }
  MinimaxSqpOptions so;
  so.max_iterations = options.max_iterations;
  const MinimaxSqpResult r = minimise_max(
      [&](const Eigen::VectorXd& x, Eigen::VectorXd& phi, Eigen::MatrixXd& g) { deviation(x, phi, g); },
      deviation.variables_of(first, first_axis), lower, upper, so);
  result.iterations = r.iterations;

  // The better of the start and the optimiser's answer, never worse than the start.
  result.base = first;
  result.axis = first_axis;
  result.max_angle = measure_quasi_revolution(samples, first, first_axis).max_angle;
  std::vector<double> c(start.coefficients().size(), 0.0);
  for (std::size_t i = 2; i < c.size(); ++i) c[i] = r.x(static_cast<Eigen::Index>(i) - 2);
  BaseAxis axis = first_axis;
  if (options.search_axis) axis = {r.x(n - 4), r.x(n - 3), r.x(n - 2), r.x(n - 1)};
  const BaseSurface base =
      with_height_offset(samples, BaseSurface(start.degree(), start.knots(), c), axis);
  const double max_angle = measure_quasi_revolution(samples, base, axis).max_angle;
  if (max_angle <= result.max_angle) {
    result.base = base;
    result.axis = axis;
    result.max_angle = max_angle;
  }
  result.status = r.status;
  return result;
}

}  // namespace freeturn
