#include "freeturn/nurbs/interpolation.hpp"

#include <Eigen/SparseLU>
#include <string>

#include "collocation.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/nurbs/parameterization.hpp"

namespace freeturn::nurbs {
namespace {

using Eigen::MatrixXd;

// Solves N X = B for the collocation matrix of (knots, params), B with any number of
// columns. The matrix is banded and totally positive; sparse LU factors it once.
MatrixXd solve_collocation(const KnotVector& knots, const std::vector<double>& params,
                           const MatrixXd& rhs) {
  SparseMatrix n = collocation_matrix(knots, params);
  n.makeCompressed();
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(n);
  if (lu.info() != Eigen::Success)
    throw InputError("interpolation",
                     "the collocation matrix is singular: the parameters do not "
                     "suit the knots (Schoenberg–Whitney condition)");
  return lu.solve(rhs);
}

void check_parameters(const std::vector<double>& params, std::size_t count) {
  if (params.size() != count)
    throw InputError("parameters", std::to_string(params.size()) + " parameters for " +
                                       std::to_string(count) + " points");
  for (std::size_t k = 1; k < params.size(); ++k)
    if (!(params[k] > params[k - 1]))
      throw InputError("parameter " + std::to_string(k), "must be greater than the one before");
}

}  // namespace

NurbsCurve interpolate_curve(const std::vector<Vector3d>& points, int degree,
                             std::vector<double> params) {
  if (params.empty()) params = chord_length_parameters(points);
  check_parameters(params, points.size());
  KnotVector knots(degree, averaged_knots(params, degree));
  MatrixXd q(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k)
    q.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  const MatrixXd p = solve_collocation(knots, params, q);
  std::vector<Vector4d> pw(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    pw[i] << p.row(static_cast<Eigen::Index>(i)).transpose(), 1.0;
  return NurbsCurve(std::move(knots), std::move(pw));
}

NurbsSurface interpolate_surface(const std::vector<Vector3d>& grid, int rows, int cols,
                                 int degree_u, int degree_v, const GridParameters* given) {
  const GridParameters params = given ? *given : grid_parameters(grid, rows, cols);
  if (static_cast<int>(params.u.size()) != rows || static_cast<int>(params.v.size()) != cols)
    throw InputError("params", "need one parameter per row (" + std::to_string(rows) +
                                   ") and per column (" + std::to_string(cols) + ")");
  const std::vector<double>& uk = params.u;
  const std::vector<double>& vl = params.v;
  KnotVector ku(degree_u, averaged_knots(uk, degree_u));
  KnotVector kv(degree_v, averaged_knots(vl, degree_v));
  // Along u for every column at once: rows × (3·cols) right-hand sides.
  MatrixXd q(rows, 3 * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) q.block(i, 3 * j, 1, 3) = grid[i * cols + j].transpose();
  const MatrixXd r = solve_collocation(ku, uk, q);  // rows × 3·cols
  // Then along v for every row of R: cols × (3·rows).
  MatrixXd q2(cols, 3 * rows);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) q2.block(j, 3 * i, 1, 3) = r.block(i, 3 * j, 1, 3);
  const MatrixXd p = solve_collocation(kv, vl, q2);
  std::vector<Vector4d> pw(static_cast<std::size_t>(rows) * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) pw[i * cols + j] << p.block(j, 3 * i, 1, 3).transpose(), 1.0;
  return NurbsSurface(std::move(ku), std::move(kv), std::move(pw));
}

}  // namespace freeturn::nurbs
