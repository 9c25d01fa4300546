#include "freeturn/core/minimax_sqp.hpp"

#include <algorithm>
#include <cmath>

#include "freeturn/core/dense_qp.hpp"

namespace freeturn {

MinimaxSqpResult minimise_max(const MinimaxFunctions& functions, const Eigen::VectorXd& x0,
                              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                              const MinimaxSqpOptions& options) {
  const int n = static_cast<int>(x0.size());
  MinimaxSqpResult out;
  Eigen::VectorXd x = x0.cwiseMax(lower).cwiseMin(upper);
  Eigen::VectorXd phi, trial_phi;
  Eigen::MatrixXd grad, trial_grad;
  functions(x, phi, grad);
  const int m = static_cast<int>(phi.size());
  out.x = x;
  out.value = m ? phi.maxCoeff() : 0.0;
  if (m == 0 || n == 0) {
    out.status = Status::kOk;
    return out;
  }
  double value = out.value;

  // x = x_start + scale ∘ y: unit steps in y move the functions alike.
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) {
    const double g = grad.col(i).cwiseAbs().maxCoeff();
    scale(i) = g > 0 ? 1 / g : 1.0;
  }
  // In y, the model's curvature starts small (the step is the trust region's, as in
  // sequential linear programming) and BFGS learns the rest.
  Eigen::MatrixXd B = Eigen::MatrixXd::Identity(n, n) * 1e-6;
  // A first step that may change the functions by about their largest value (or 1 %).
  double radius = std::max(std::abs(value), 1e-2);

  // The QP in (d, τ), τ = the model's max minus F(x): minimise τ + ½τ² + ½ dᵀBd subject to
  // τ − g_kᵀd ≥ φ_k − F, |d_i| ≤ Δ, and the bounds. The ½τ² keeps the QP strictly convex;
  // at the τ of a step (|τ| ≪ 1) it weighs the decrease by 1 + τ, not 1.
  int bound_rows = 0;
  for (int i = 0; i < n; ++i) bound_rows += (lower(i) > -1e300) + (upper(i) < 1e300);
  Eigen::MatrixXd C(m + 2 * n + bound_rows, n + 1);
  Eigen::VectorXd b(C.rows());
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n + 1);
  a(n) = 1;

  for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
    for (int k = 0; k < m; ++k) {
      C.row(k).head(n) = -(grad.row(k).array() * scale.transpose().array()).matrix();
      C(k, n) = 1;
      b(k) = phi(k) - value;
    }
    int row = m;
    for (int i = 0; i < n; ++i) {
      C.row(row).setZero(), C(row, i) = 1, b(row++) = -radius;
      C.row(row).setZero(), C(row, i) = -1, b(row++) = -radius;
      if (lower(i) > -1e300) C.row(row).setZero(), C(row, i) = 1, b(row++) = (lower(i) - x(i)) / scale(i);
      if (upper(i) < 1e300) C.row(row).setZero(), C(row, i) = -1, b(row++) = (x(i) - upper(i)) / scale(i);
    }
    G.topLeftCorner(n, n) = B;
    G(n, n) = 1;
    const DenseQpResult qp = solve_dense_qp(G, a, C, b, 1e-15);
    if (qp.status != Status::kOk) break;
    const Eigen::VectorXd d = qp.x.head(n);
    const double tau = qp.x(n);
    const double predicted = -(tau + 0.5 * d.dot(B * d));
    if (!(predicted > options.decrease_tolerance)) {
      out.status = Status::kOk;
      break;
    }
    Eigen::VectorXd trial = (x + scale.cwiseProduct(d)).cwiseMax(lower).cwiseMin(upper);
    functions(trial, trial_phi, trial_grad);
    const double trial_value = trial_phi.maxCoeff();
    const double ratio = (value - trial_value) / predicted;
    const double step = d.cwiseAbs().maxCoeff();
    if (ratio > 0.1) {
      // The Lagrangian's gradient change with the QP's multipliers of the function rows.
      Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
      double weight = 0;
      for (std::size_t j = 0; j < qp.active.size(); ++j) {
        const int k = qp.active[j];
        if (k >= m) continue;
        const double lambda = qp.multipliers[j];
        y += lambda * ((trial_grad.row(k) - grad.row(k)).transpose().cwiseProduct(scale));
        weight += lambda;
      }
      if (weight > 0) y /= weight;
      const Eigen::VectorXd Bd = B * d;
      const double dBd = d.dot(Bd), dy = d.dot(y);
      if (dBd > 0) {
        // Powell's damping keeps B positive definite where the curvature is negative.
        const double theta = dy >= 0.2 * dBd ? 1.0 : 0.8 * dBd / (dBd - dy);
        const Eigen::VectorXd r = theta * y + (1 - theta) * Bd;
        const double dr = d.dot(r);
        if (dr > 1e-300) B += r * r.transpose() / dr - Bd * Bd.transpose() / dBd;
        // Where the functions are linear the damping shrinks B along every step: keep it
        // away from singular (the QP factors it).
        if (B.diagonal().minCoeff() < 1e-10) B.diagonal().array() += 1e-10;
      }
      x = trial;
      phi.swap(trial_phi);
      grad.swap(trial_grad);
      value = trial_value;
      if (ratio > 0.75 && step > 0.99 * radius) radius *= 2;
    } else {
      radius = 0.25 * step;
    }
    if (radius < 1e-15) {
      out.status = Status::kOk;  // no step the model trusts changes F
      break;
    }
  }
  out.x = x;
  out.value = value;
  return out;
}

}  // namespace freeturn
