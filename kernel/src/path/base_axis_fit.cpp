#include "freeturn/path/base_axis_fit.hpp"

#include <cmath>
#include <unsupported/Eigen/LevenbergMarquardt>

#include "revolution_terms.hpp"

namespace freeturn {
namespace {

// Residuals (r_k, n_θ,k) for every sample; unknowns c_2 … c_{n−1}, then the axis.
struct AngleResiduals : Eigen::DenseFunctor<double> {
  AngleResiduals(const std::vector<SurfaceSample>& samples, const BaseSurface& start)
      : Eigen::DenseFunctor<double>(static_cast<int>(start.coefficients().size()) - 2 + 4,
                                    static_cast<int>(2 * samples.size())),
        samples_(samples), free_(static_cast<int>(start.coefficients().size()) - 2),
        degree_(start.degree()), knots_(start.knots()) {}

  int operator()(const InputType& x, ValueType& f) const {
    detail::BaseSlope slope(degree_, knots_);
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      const detail::RevolutionTerms t = detail::revolution_terms(samples_[k], x.data() + free_);
      slope.evaluate(t.rho.value(), x.data());
      const double hp = slope.slope, norm = std::sqrt(1 + hp * hp);
      f(2 * k) = (t.n_rho.value() + t.n_h.value() * hp) / norm;
      f(2 * k + 1) = t.n_theta.value();
    }
    return 0;
  }

  int df(const InputType& x, JacobianType& j) const {
    j.setZero();
    detail::BaseSlope slope(degree_, knots_);
    for (std::size_t k = 0; k < samples_.size(); ++k) {
      const detail::RevolutionTerms t = detail::revolution_terms(samples_[k], x.data() + free_);
      slope.evaluate(t.rho.value(), x.data());
      const detail::AxisAd hp(slope.slope, slope.curvature * t.rho.derivatives());
      const detail::AxisAd r = (t.n_rho + t.n_h * hp) / sqrt(1.0 + hp * hp);
      const double h = hp.value();
      // ∂r/∂H' = (n_h − n_ρ H')/(1 + H'²)^{3/2}.
      const double dr_dslope = (t.n_h.value() - t.n_rho.value() * h) / std::pow(1 + h * h, 1.5);
      for (int b = 0; b < slope.count(); ++b) {
        const int i = slope.first() + b;
        if (i >= 2) j(2 * k, i - 2) = dr_dslope * slope.basis_slope(b);
      }
      for (int a = 0; a < 4; ++a) {
        j(2 * k, free_ + a) = r.derivatives()(a);
        j(2 * k + 1, free_ + a) = t.n_theta.derivatives()(a);
      }
    }
    return 0;
  }

  const std::vector<SurfaceSample>& samples_;
  int free_, degree_;
  std::vector<double> knots_;
};

}  // namespace

BaseSurface with_height_offset(const std::vector<SurfaceSample>& samples, const BaseSurface& base,
                               const BaseAxis& axis) {
  const Eigen::Vector3d t = axis.direction(), o = axis.point();
  double offset = 0;
  for (const SurfaceSample& s : samples) {
    const Eigen::Vector3d d = s.point - o;
    const double h = d.dot(t);
    offset += h - base.at_radius((d - h * t).norm()).h;
  }
  offset /= static_cast<double>(std::max<std::size_t>(samples.size(), 1));
  std::vector<double> c = base.coefficients();
  for (double& v : c) v += offset;
  return BaseSurface(base.degree(), base.knots(), c);
}

BaseAxisFit fit_base_and_axis_least_squares(const std::vector<SurfaceSample>& samples,
                                            const BaseSurface& start) {
  AngleResiduals residuals(samples, start);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(residuals.inputs());
  const std::vector<double>& c = start.coefficients();
  for (int i = 2; i < static_cast<int>(c.size()); ++i) x(i - 2) = c[i] - c[0];
  Eigen::LevenbergMarquardt<AngleResiduals> lm(residuals);
  lm.setXtol(1e-14);
  lm.setFtol(1e-16);
  lm.setMaxfev(400);
  const Eigen::LevenbergMarquardtSpace::Status status = lm.minimize(x);
  BaseAxisFit fit{start, {}};
  fit.iterations = static_cast<int>(lm.iterations());
  fit.status = status == Eigen::LevenbergMarquardtSpace::TooManyFunctionEvaluation ||
                       status == Eigen::LevenbergMarquardtSpace::ImproperInputParameters
                   ? Status::kNotConverged
                   : Status::kOk;
  const int free = residuals.free_;
  fit.axis = {x(free), x(free + 1), x(free + 2), x(free + 3)};
  std::vector<double> coefficients(c.size(), 0.0);
  for (int i = 2; i < static_cast<int>(c.size()); ++i) coefficients[i] = x(i - 2);
  fit.base = with_height_offset(samples, BaseSurface(start.degree(), start.knots(), coefficients),
                                fit.axis);
  const QuasiRevolution q = measure_quasi_revolution(samples, fit.base, fit.axis);
  fit.max_angle = q.max_angle;
  fit.rms_angle = q.rms_angle;
  return fit;
}

}  // namespace freeturn
