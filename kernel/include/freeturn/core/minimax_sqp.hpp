#pragma once
// The smallest largest of m smooth functions of a few variables:
//
//   minimise F(x) = max_k φ_k(x)   over   lower ≤ x ≤ upper,
//
// by sequential quadratic programming on the epigraph (a trust-region SQP for minimax
// problems; R. Fletcher, Practical Methods of Optimization, 2nd ed., 1987, §14.5): at x,
// the model max_k (φ_k + ∇φ_kᵀ d) + ½ dᵀ B d over the trust region ‖d‖∞ ≤ Δ is minimised
// as a dense QP (core/dense_qp.hpp: every row, few of them active); the step is taken when
// the actual decrease of F is a fair share of the model's; B is a damped BFGS estimate
// (M. J. D. Powell, 1978) of the Hessian of the Lagrangian Σ λ_k φ_k with the QP's
// multipliers. Variables are scaled by the inverse of their largest gradient entry at
// the start, so that a unit step in each moves the functions alike.
//
// For tens of variables and thousands of functions: each iteration evaluates every φ_k
// and its gradient once, then a QP whose cost grows with the active rows, not with m.

#include <Eigen/Core>
#include <functional>

#include "freeturn/core/status.hpp"

namespace freeturn {

// Fills phi (m) with φ_k(x) and gradients (m × n) with ∇φ_kᵀ, row k.
using MinimaxFunctions =
    std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& phi, Eigen::MatrixXd& gradients)>;

struct MinimaxSqpOptions {
  int max_iterations = 300;
  // Converged when the model predicts a decrease of F below this (F's units).
  double decrease_tolerance = 1e-13;
};

struct MinimaxSqpResult {
  Eigen::VectorXd x;
  double value = 0;  // F(x)
  int iterations = 0;
  Status status = Status::kNotConverged;
};

// lower, upper: n (±infinity where unbounded); x0 is clamped into them.
MinimaxSqpResult minimise_max(const MinimaxFunctions& functions, const Eigen::VectorXd& x0,
                              const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                              const MinimaxSqpOptions& options = {});

}  // namespace freeturn
