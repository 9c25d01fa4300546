#include "freeturn/nurbs/parameterization.hpp"

#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"

namespace freeturn::nurbs {

std::vector<double> chord_length_parameters(const std::vector<Vector3d>& points, bool centripetal) {
  const std::size_t n = points.size();
  if (n < 2) throw InputError("points", "at least 2 points are needed, got " + std::to_string(n));
  std::vector<double> u(n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    if (!points[k].allFinite())
      throw InputError("point " + std::to_string(k), "has a coordinate that is not finite");
  for (std::size_t k = 1; k < n; ++k) {
    const double chord = (points[k] - points[k - 1]).norm();
    if (chord == 0)
      throw InputError("point " + std::to_string(k),
                       "coincides with point " + std::to_string(k - 1) +
                           ": parameters need distinct consecutive points");
    u[k] = u[k - 1] + (centripetal ? std::sqrt(chord) : chord);
  }
  const double total = u.back();
  for (double& x : u) x /= total;
  u.back() = 1.0;
  return u;
}

GridParameters grid_parameters(const std::vector<Vector3d>& grid, int rows, int cols) {
  if (rows < 2 || cols < 2 || grid.size() != static_cast<std::size_t>(rows) * cols)
    throw InputError("grid", std::to_string(grid.size()) + " points do not form a " +
                                 std::to_string(rows) + " x " + std::to_string(cols) + " grid");
  GridParameters g{std::vector<double>(static_cast<std::size_t>(rows), 0.0),
                   std::vector<double>(static_cast<std::size_t>(cols), 0.0)};
  std::vector<Vector3d> line;
  for (int j = 0; j < cols; ++j) {
    line.clear();
    for (int i = 0; i < rows; ++i) line.push_back(grid[i * cols + j]);
    const auto t = chord_length_parameters(line);
    for (int i = 0; i < rows; ++i) g.u[i] += t[i] / cols;
  }
  for (int i = 0; i < rows; ++i) {
    line.assign(grid.begin() + i * cols, grid.begin() + (i + 1) * cols);
    const auto t = chord_length_parameters(line);
    for (int j = 0; j < cols; ++j) g.v[j] += t[j] / rows;
  }
  g.u.back() = g.v.back() = 1.0;
  return g;
}

std::vector<double> averaged_knots(const std::vector<double>& params, int degree) {
  const int n = static_cast<int>(params.size()) - 1;
  const int p = degree;
  if (n < p)
    throw InputError("points",
                     std::to_string(n + 1) + " points are too few for degree " + std::to_string(p));
  std::vector<double> U(static_cast<std::size_t>(n + p + 2), 0.0);
  for (int i = n + 1; i <= n + p + 1; ++i) U[i] = 1.0;
  for (int j = 1; j <= n - p; ++j) {
    double sum = 0;
    for (int i = j; i <= j + p - 1; ++i) sum += params[i];
    U[j + p] = sum / p;
  }
  return U;
}

std::vector<double> approximation_knots(const std::vector<double>& params, int degree, int count) {
  const int m = static_cast<int>(params.size()) - 1;  // data points 0..m
  const int n = count - 1;                            // control points 0..n
  const int p = degree;
  if (n < p)
    throw InputError("control points",
                     std::to_string(count) + " are too few for degree " + std::to_string(p));
  if (m < n)
    throw InputError("points", std::to_string(m + 1) + " points are too few for " +
                                   std::to_string(count) + " control points");
  std::vector<double> U(static_cast<std::size_t>(n + p + 2), 0.0);
  for (int i = n + 1; i <= n + p + 1; ++i) U[i] = 1.0;
  const double d = static_cast<double>(m + 1) / (n - p + 1);  // Eq. 9.68
  for (int j = 1; j <= n - p; ++j) {                          // Eq. 9.69
    const int i = static_cast<int>(j * d);
    const double alpha = j * d - i;
    U[p + j] = (1.0 - alpha) * params[i - 1] + alpha * params[i];
  }
  return U;
}

}  // namespace freeturn::nurbs
