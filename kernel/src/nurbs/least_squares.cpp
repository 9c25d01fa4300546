#include "freeturn/nurbs/least_squares.hpp"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "collocation.hpp"
#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/curve_locator.hpp"
#include "freeturn/nurbs/parameterization.hpp"
#include "freeturn/nurbs/surface_locator.hpp"

namespace freeturn::nurbs {
namespace {

using Eigen::MatrixXd;

void check_params(const std::vector<double>& params, std::size_t count, const char* what) {
  if (params.size() != count)
    throw InputError(what, std::to_string(params.size()) + " parameters for " +
                               std::to_string(count) + " points");
  for (std::size_t k = 0; k < params.size(); ++k)
    if (!(std::isfinite(params[k]) && params[k] >= 0 && params[k] <= 1))
      throw InputError(std::string(what) + " " + std::to_string(k), "must lie in [0, 1]");
}

// Solves the symmetric positive definite system A X = B, with the rows in `fixed` held at
// the values given in X on entry (eliminated from the system).
MatrixXd solve_normal_equations(const SparseMatrix& a, const MatrixXd& b,
                                const std::vector<bool>& fixed, MatrixXd x) {
  const int n = static_cast<int>(a.rows());
  std::vector<int> index(static_cast<std::size_t>(n), -1);
  int free_count = 0;
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) index[i] = free_count++;
  // A diagonal entry of zero means a control point with no data and no smoothing.
  for (int i = 0; i < n; ++i)
    if (!fixed[i] && !(a.coeff(i, i) > 0))
      throw InputError("control point " + std::to_string(i),
                       "has no data under its basis function: use fewer control points or add "
                       "smoothing");
  std::vector<Eigen::Triplet<double>> t;
  MatrixXd rhs = MatrixXd::Zero(free_count, b.cols());
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) rhs.row(index[i]) = b.row(i);
  for (int c = 0; c < a.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(a, c); it; ++it) {
      const int r = static_cast<int>(it.row()), col = static_cast<int>(it.col());
      if (fixed[r]) continue;
      if (fixed[col])
        rhs.row(index[r]) -= it.value() * x.row(col);
      else
        t.emplace_back(index[r], index[col], it.value());
    }
  SparseMatrix af(free_count, free_count);
  af.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(af);
  if (ldlt.info() != Eigen::Success)
    throw InputError("least squares",
                     "the normal equations are singular: use fewer control "
                     "points or add smoothing");
  const MatrixXd xf = ldlt.solve(rhs);
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) x.row(i) = xf.row(index[i]);
  return x;
}

// A smoothing weight λ this many times the data's own weight (the largest diagonal entries
// of λ·E's matrix against NᵀN's) fits the energy's null space, a line or a plane, whatever
// the data, and λ·E's rounding, about 1e-16 of it, then moves the fit by ε·λ‖E‖/‖NᵀN‖ of
// its size (1e16 turned a 3 mm grid's x-y into 7 µm). At 1e8 that is parts in 1e8, well
// below a nanometre over a part, and the fit is long past any smoothing a user means.
constexpr double kMaxSmoothingWeight = 1e8;

double largest_diagonal(const SparseMatrix& m) {
  double largest = 0;
  for (Eigen::Index i = 0; i < std::min(m.rows(), m.cols()); ++i)
    largest = std::max(largest, std::abs(m.coeff(i, i)));
  return largest;
}

void check_smoothing_weight(double smoothing, double data_weight, double energy_weight) {
  if (!(smoothing > 0 && energy_weight > 0 && data_weight > 0)) return;
  const double limit = kMaxSmoothingWeight * data_weight / energy_weight;
  if (smoothing > limit)
    throw InputError("smoothing", "is " + shortest_text(smoothing) +
                                      ", more than 1e8 times the data's own weight (at most " +
                                      significant_text(limit, 3) +
                                      " for these points and control points): the fit would be "
                                      "the smoothest surface whatever the data, and rounding "
                                      "would move it");
}

KnotVector fit_knots(const std::vector<double>& given, const std::vector<double>& params,
                     int degree, int count) {
  KnotVector k = given.empty() ? KnotVector(degree, approximation_knots(params, degree, count))
                               : KnotVector(degree, given);
  if (!k.is_clamped()) throw InputError("knots", "fitting needs clamped knots");
  return k;
}

// One least-squares solve of a curve at fixed parameters.
NurbsCurve solve_curve(const std::vector<Vector3d>& points, const std::vector<double>& params,
                       const KnotVector& knots, double smoothing, bool pin_ends) {
  const SparseMatrix n = collocation_matrix(knots, params);
  SparseMatrix a = SparseMatrix(n.transpose()) * n;
  if (smoothing > 0) {
    const SparseMatrix energy = derivative_gram_matrix(knots, 2);
    check_smoothing_weight(smoothing, largest_diagonal(a), largest_diagonal(energy));
    a += smoothing * energy;
  }
  MatrixXd q(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k)
    q.row(static_cast<Eigen::Index>(k)) = points[k].transpose();
  const MatrixXd b = n.transpose() * q;
  const int count = knots.count();
  std::vector<bool> fixed(static_cast<std::size_t>(count), false);
  MatrixXd x = MatrixXd::Zero(count, 3);
  if (pin_ends) {  // clamped knots: the end control points are the end points
    fixed.front() = fixed.back() = true;
    x.row(0) = points.front().transpose();
    x.row(count - 1) = points.back().transpose();
  }
  x = solve_normal_equations(a, b, fixed, std::move(x));
  std::vector<Vector4d> pw(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) pw[i] << x.row(i).transpose(), 1.0;
  return NurbsCurve(knots, std::move(pw));
}

}  // namespace

CurveFit fit_curve(const std::vector<Vector3d>& points, const CurveFitOptions& options) {
  if (!(options.smoothing >= 0 && std::isfinite(options.smoothing)))
    throw InputError("smoothing", "must be a finite number >= 0");
  CurveFit fit;
  fit.params = options.params.empty() ? chord_length_parameters(points) : options.params;
  check_params(fit.params, points.size(), "parameter");
  const KnotVector knots = fit_knots(options.knots, fit.params, options.degree, options.count);
  fit.curve = solve_curve(points, fit.params, knots, options.smoothing, options.pin_ends);
  for (int round = 0; round < options.parameter_corrections; ++round) {
    const CurveLocator locator(fit.curve);
    for (std::size_t k = 0; k < points.size(); ++k)
      fit.params[k] = locator.closest_point(points[k], fit.params[k]).u;
    if (options.pin_ends) {
      fit.params.front() = 0.0;
      fit.params.back() = 1.0;
    }
    fit.curve = solve_curve(points, fit.params, knots, options.smoothing, options.pin_ends);
  }
  double sum = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double e = (fit.curve.point(fit.params[k]) - points[k]).norm();
    fit.max_error = std::max(fit.max_error, e);
    sum += e * e;
  }
  fit.rms_error = std::sqrt(sum / static_cast<double>(points.size()));
  return fit;
}

namespace {

void measure(SurfaceFit& fit, const std::vector<Vector3d>& points) {
  double sum = 0;
  fit.max_error = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double e = (fit.surface.point(fit.u[k], fit.v[k]) - points[k]).norm();
    fit.max_error = std::max(fit.max_error, e);
    sum += e * e;
  }
  fit.rms_error = std::sqrt(sum / static_cast<double>(points.size()));
}

}  // namespace

SurfaceFit fit_surface_grid(const std::vector<Vector3d>& grid, int rows, int cols,
                            const SurfaceFitOptions& options) {
  GridParameters params;
  if (options.params_u.empty() && options.params_v.empty()) {
    params = grid_parameters(grid, rows, cols);
  } else {
    params = {options.params_u, options.params_v};
    if (static_cast<int>(params.u.size()) != rows || static_cast<int>(params.v.size()) != cols)
      throw InputError("params", "need one parameter per row (" + std::to_string(rows) +
                                     ") and per column (" + std::to_string(cols) + ")");
  }
  const std::vector<double>& uk = params.u;
  const std::vector<double>& vl = params.v;
  const KnotVector ku = fit_knots(options.knots_u, uk, options.degree_u, options.count_u);
  const KnotVector kv = fit_knots(options.knots_v, vl, options.degree_v, options.count_v);

  // Separable solve: (NuᵀNu) R = Nuᵀ Q column by column, then (NvᵀNv) Pᵀ = Nvᵀ Rᵀ.
  const auto solve_direction = [&](const KnotVector& k, const std::vector<double>& t,
                                   const MatrixXd& q) {
    const SparseMatrix n = collocation_matrix(k, t);
    SparseMatrix a = SparseMatrix(n.transpose()) * n;
    if (options.smoothing > 0) {
      const SparseMatrix energy = derivative_gram_matrix(k, 2);
      check_smoothing_weight(options.smoothing, largest_diagonal(a), largest_diagonal(energy));
      a += options.smoothing * energy;
    }
    const std::vector<bool> fixed(static_cast<std::size_t>(k.count()), false);
    return solve_normal_equations(a, n.transpose() * q, fixed, MatrixXd::Zero(k.count(), q.cols()));
  };
  MatrixXd q(rows, 3 * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) q.block(i, 3 * j, 1, 3) = grid[i * cols + j].transpose();
  const MatrixXd r = solve_direction(ku, uk, q);  // count_u × 3·cols
  const int nu = ku.count(), nv = kv.count();
  MatrixXd q2(cols, 3 * nu);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < cols; ++j) q2.block(j, 3 * i, 1, 3) = r.block(i, 3 * j, 1, 3);
  const MatrixXd p = solve_direction(kv, vl, q2);  // count_v × 3·count_u
  std::vector<Vector4d> pw(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) pw[i * nv + j] << p.block(j, 3 * i, 1, 3).transpose(), 1.0;

  SurfaceFit fit{NurbsSurface(ku, kv, std::move(pw)), {}, {}, 0, 0};
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      fit.u.push_back(uk[i]);
      fit.v.push_back(vl[j]);
    }
  measure(fit, grid);
  return fit;
}

namespace {

// One least-squares solve on scattered data. The normal matrix is block-banded: control
// points (i, j) and (i', j') interact only when |i − i'| ≤ p and |j − j'| ≤ q, so it is
// accumulated densely per row over those (2p + 1)(2q + 1) neighbours and converted once.
NurbsSurface solve_scattered(const std::vector<Vector3d>& points, const std::vector<double>& u,
                             const std::vector<double>& v, const KnotVector& ku,
                             const KnotVector& kv, double smoothing) {
  const int p = ku.degree(), q = kv.degree();
  const int nu = ku.count(), nv = kv.count(), n = nu * nv;
  const int wu = 2 * p + 1, wv = 2 * q + 1, band = wu * wv;
  std::vector<double> acc(static_cast<std::size_t>(n) * band, 0.0);
  MatrixXd b = MatrixXd::Zero(n, 3);
  std::vector<double> bu(static_cast<std::size_t>(p + 1)), bv(static_cast<std::size_t>(q + 1));
  const auto add = [&](int r, int c, double value) {
    const int di = c / nv - r / nv + p, dj = c % nv - r % nv + q;
    acc[static_cast<std::size_t>(r) * band + di * wv + dj] += value;
  };
  int su = p, sv = q;
  for (std::size_t k = 0; k < points.size(); ++k) {
    su = ku.find_span(u[k], su);
    sv = kv.find_span(v[k], sv);
    basis_functions(su, u[k], p, ku.knots().data(), bu.data());
    basis_functions(sv, v[k], q, kv.knots().data(), bv.data());
    for (int a = 0; a <= p; ++a)
      for (int c = 0; c <= q; ++c) {
        const int r = (su - p + a) * nv + (sv - q + c);
        const double w = bu[a] * bv[c];
        b.row(r) += w * points[k].transpose();
        for (int a2 = 0; a2 <= p; ++a2)
          for (int c2 = 0; c2 <= q; ++c2)
            add(r, (su - p + a2) * nv + (sv - q + c2), w * bu[a2] * bv[c2]);
      }
  }
  if (smoothing > 0) {
    // Thin-plate energy as Kronecker products of 1D Gram matrices:
    // G2u⊗G0v + 2·G1u⊗G1v + G0u⊗G2v.
    const SparseMatrix g[3] = {derivative_gram_matrix(ku, 0), derivative_gram_matrix(ku, 1),
                               derivative_gram_matrix(ku, 2)};
    const SparseMatrix h[3] = {derivative_gram_matrix(kv, 0), derivative_gram_matrix(kv, 1),
                               derivative_gram_matrix(kv, 2)};
    const std::pair<int, int> terms[3] = {{2, 0}, {1, 1}, {0, 2}};
    const double factor[3] = {1.0, 2.0, 1.0};
    double data_weight = 0, energy_weight = 0;
    for (int r = 0; r < n; ++r)
      data_weight = std::max(data_weight, acc[static_cast<std::size_t>(r) * band + p * wv + q]);
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        double diagonal = 0;
        for (int t = 0; t < 3; ++t)
          diagonal += factor[t] * g[terms[t].first].coeff(i, i) * h[terms[t].second].coeff(j, j);
        energy_weight = std::max(energy_weight, diagonal);
      }
    check_smoothing_weight(smoothing, data_weight, energy_weight);
    for (int t = 0; t < 3; ++t) {
      const SparseMatrix& gu = g[terms[t].first];
      const SparseMatrix& gv = h[terms[t].second];
      for (int cu = 0; cu < gu.outerSize(); ++cu)
        for (SparseMatrix::InnerIterator iu(gu, cu); iu; ++iu)
          for (int cv = 0; cv < gv.outerSize(); ++cv)
            for (SparseMatrix::InnerIterator iv(gv, cv); iv; ++iv)
              add(static_cast<int>(iu.row()) * nv + static_cast<int>(iv.row()),
                  static_cast<int>(iu.col()) * nv + static_cast<int>(iv.col()),
                  smoothing * factor[t] * iu.value() * iv.value());
    }
  }
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(acc.size());
  for (int r = 0; r < n; ++r)
    for (int di = 0; di < wu; ++di)
      for (int dj = 0; dj < wv; ++dj) {
        const double value = acc[static_cast<std::size_t>(r) * band + di * wv + dj];
        if (value == 0) continue;
        const int i = r / nv + di - p, j = r % nv + dj - q;
        trip.emplace_back(r, i * nv + j, value);
      }
  SparseMatrix a(n, n);
  a.setFromTriplets(trip.begin(), trip.end());
  const std::vector<bool> fixed(static_cast<std::size_t>(n), false);
  MatrixXd x;
  try {
    x = solve_normal_equations(a, b, fixed, MatrixXd::Zero(n, 3));
  } catch (const InputError& e) {
    if (e.where().rfind("control point ", 0) != 0) throw;
    const int index = std::stoi(e.where().substr(14));
    throw InputError(
        "control point " + std::to_string(index / nv) + "," + std::to_string(index % nv),
        e.problem());
  }
  std::vector<Vector4d> pw(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) pw[r] << x.row(r).transpose(), 1.0;
  return NurbsSurface(ku, kv, std::move(pw));
}

KnotVector uniform_or_given(const std::vector<double>& given, int degree, int count) {
  if (!given.empty()) {
    KnotVector k(degree, given);
    if (!k.is_clamped()) throw InputError("knots", "fitting needs clamped knots");
    return k;
  }
  return KnotVector::uniform_clamped(degree, count);
}

}  // namespace

SurfaceFit fit_surface_scattered(const std::vector<Vector3d>& points, std::vector<double> u,
                                 std::vector<double> v, const SurfaceFitOptions& options) {
  if (!(options.smoothing >= 0 && std::isfinite(options.smoothing)))
    throw InputError("smoothing", "must be a finite number >= 0");
  check_params(u, points.size(), "u parameter");
  check_params(v, points.size(), "v parameter");
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!points[k].allFinite())
      throw InputError("point " + std::to_string(k), "has a coordinate that is not finite");
  const KnotVector ku = uniform_or_given(options.knots_u, options.degree_u, options.count_u);
  const KnotVector kv = uniform_or_given(options.knots_v, options.degree_v, options.count_v);
  SurfaceFit fit{solve_scattered(points, u, v, ku, kv, options.smoothing), std::move(u),
                 std::move(v), 0, 0};
  for (int round = 0; round < options.parameter_corrections; ++round) {
    const SurfaceLocator locator(fit.surface);
    for (std::size_t k = 0; k < points.size(); ++k) {
      const SurfacePointResult r = locator.closest_point(points[k], fit.u[k], fit.v[k]);
      fit.u[k] = r.u;
      fit.v[k] = r.v;
    }
    fit.surface = solve_scattered(points, fit.u, fit.v, ku, kv, options.smoothing);
  }
  measure(fit, points);
  return fit;
}

}  // namespace freeturn::nurbs
