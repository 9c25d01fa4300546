#pragma once
// A strictly convex quadratic programme with inequality constraints, dense and small in
// its variables (tens), any number of constraints:
//
//   minimise ½ xᵀ G x + aᵀ x   subject to   C x ≥ b      (G symmetric positive definite)
//
// Goldfarb & Idnani's dual active-set method (D. Goldfarb, A. Idnani, "A numerically stable
// dual method for solving strictly convex quadratic programs", Mathematical Programming
// 27, 1983): it starts at the unconstrained minimum and adds the most violated
// constraint, dropping one whose multiplier would turn negative, keeping the active
// constraints' QR factors (J = L⁻ᵀQ, R) up to date by Givens rotations. Each step costs
// O(n²) besides one pass over the constraints to find the most violated, so thousands of
// rows of which a handful are active cost little: the shape of a minimax subproblem.

#include <Eigen/Core>
#include <vector>

#include "freeturn/core/status.hpp"

namespace freeturn {

struct DenseQpResult {
  Eigen::VectorXd x;             // n
  double objective = 0;          // ½ xᵀGx + aᵀx at x
  std::vector<int> active;       // rows of C active at x
  std::vector<double> multipliers;  // one per active row, ≥ 0
  Status status = Status::kOk;   // kNotConverged if infeasible or out of steps
};

// G: n × n, a: n, C: m × n (one constraint per row), b: m. `feasibility`: how far below
// its bound a row may stay (absolute).
DenseQpResult solve_dense_qp(const Eigen::MatrixXd& G, const Eigen::VectorXd& a,
                             const Eigen::MatrixXd& C, const Eigen::VectorXd& b,
                             double feasibility = 1e-12);

}  // namespace freeturn
