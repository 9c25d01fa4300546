#include "freeturn/core/dense_qp.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>

namespace freeturn {
namespace {

// A Givens reflection [c s; s −c] taking (x, y) to (h, 0), h ≥ 0; applied to a pair of
// values as (c t1 + s t2, s t1 − c t2), written with ν = s/(1 + c) as in Goldfarb and
// Idnani's paper (one product fewer, and stable since c ≥ 0).
struct Reflection {
  double c = 1, s = 0, nu = 0;
  bool identity = true;
  // Sets the reflection and returns h.
  double set(double x, double y) {
    const double h = std::hypot(x, y);
    identity = h == 0;
    if (identity) return 0;
    c = x / h, s = y / h;
    if (c < 0) c = -c, s = -s;
    nu = s / (1 + c);
    return x < 0 ? -h : h;
  }
  void apply(double& t1, double& t2) const {
    const double a = t1, b = t2;
    t1 = c * a + s * b;
    t2 = nu * (a + t1) - b;
  }
};

}  // namespace

DenseQpResult solve_dense_qp(const Eigen::MatrixXd& G, const Eigen::VectorXd& a,
                             const Eigen::MatrixXd& C, const Eigen::VectorXd& b,
                             double feasibility) {
  const int n = static_cast<int>(G.rows());
  const int m = static_cast<int>(C.rows());
  constexpr double kInf = std::numeric_limits<double>::infinity();
  DenseQpResult out;
  const Eigen::LLT<Eigen::MatrixXd> llt(G);
  if (llt.info() != Eigen::Success) {
    out.status = Status::kDegenerate;
    out.x = Eigen::VectorXd::Zero(n);
    return out;
  }
  // J = L⁻ᵀ: J Jᵀ = G⁻¹. Its first q columns span the active constraints (through R).
  Eigen::MatrixXd J = Eigen::MatrixXd::Identity(n, n);
  llt.matrixU().solveInPlace(J);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd x = -llt.solve(a);
  double f = 0.5 * a.dot(x);
  std::vector<int> active;
  std::vector<double> u;  // multipliers of the active rows
  std::vector<char> is_active(static_cast<std::size_t>(m), 0);
  Eigen::VectorXd d(n), z(n), r(n);
  const double r_scale = std::max(1.0, J.cwiseAbs().maxCoeff());

  // Drops active row `l`: R loses its column and is made upper triangular again by
  // reflections of neighbouring rows, applied to J's columns too.
  const auto drop = [&](int l) {
    const int q = static_cast<int>(active.size());
    is_active[static_cast<std::size_t>(active[static_cast<std::size_t>(l)])] = 0;
    for (int k = l; k + 1 < q; ++k) R.col(k) = R.col(k + 1);
    R.col(q - 1).setZero();
    active.erase(active.begin() + l);
    u.erase(u.begin() + l);
    for (int j = l; j + 1 < q; ++j) {
      Reflection g;
      R(j, j) = g.set(R(j, j), R(j + 1, j));
      R(j + 1, j) = 0;
      if (g.identity) continue;
      for (int k = j + 1; k < q - 1; ++k) g.apply(R(j, k), R(j + 1, k));
      for (int k = 0; k < n; ++k) g.apply(J(k, j), J(k, j + 1));
    }
  };

  for (int step = 0; step < 50 * (n + m) + 100; ++step) {
    // Step 1: the most violated inactive row; none: x is optimal.
    int p = -1;
    double worst = -feasibility;
    for (int i = 0; i < m; ++i) {
      if (is_active[static_cast<std::size_t>(i)]) continue;
      const double slack = C.row(i).dot(x) - b(i);
      if (slack < worst) worst = slack, p = i;
    }
    if (p < 0) {
      out.x = x;
      out.objective = f;
      out.active = active;
      out.multipliers = u;
      return out;
    }
    double u_new = 0;  // the multiplier the new row is given as x moves to it
    // Step 2: move toward row p, dropping rows whose multipliers reach zero.
    for (;;) {
      const int q = static_cast<int>(active.size());
      d.noalias() = J.transpose() * C.row(p).transpose();
      z.noalias() = J.rightCols(n - q) * d.tail(n - q);
      for (int k = q - 1; k >= 0; --k) {  // R r = d[0:q]
        double v = d(k);
        for (int j = k + 1; j < q; ++j) v -= R(k, j) * r(j);
        r(k) = v / R(k, k);
      }
      double t1 = kInf;  // the dual step to the first multiplier at zero
      int l = -1;
      for (int k = 0; k < q; ++k)
        if (r(k) > 0 && u[static_cast<std::size_t>(k)] / r(k) < t1)
          t1 = u[static_cast<std::size_t>(k)] / r(k), l = k;
      const double znp = z.dot(C.row(p));
      const double slack = C.row(p).dot(x) - b(p);
      const double t2 = znp > 1e-14 * d.squaredNorm() && znp > 0 ? -slack / znp : kInf;
      const double t = std::min(t1, t2);
      if (t == kInf) {  // no step reaches row p: the constraints are inconsistent
        out.x = x;
        out.objective = f;
        out.status = Status::kNotConverged;
        return out;
      }
      if (t2 < kInf) {
        x += t * z;
        f += t * znp * (0.5 * t + u_new);
      }
      for (int k = 0; k < q; ++k) u[static_cast<std::size_t>(k)] -= t * r(k);
      u_new += t;
      if (t == t2) {
        // Row p joins: reflections zero d below position q, applied to J's columns, and
        // d[0:q+1] becomes R's new column.
        for (int j = n - 1; j > q; --j) {
          Reflection g;
          d(j - 1) = g.set(d(j - 1), d(j));
          d(j) = 0;
          if (g.identity) continue;
          for (int k = 0; k < n; ++k) g.apply(J(k, j - 1), J(k, j));
        }
        R.col(q).head(q + 1) = d.head(q + 1);
        if (std::abs(d(q)) <= 1e-15 * r_scale) {  // dependent on the active rows
          out.x = x;
          out.objective = f;
          out.status = Status::kDegenerate;
          return out;
        }
        active.push_back(p);
        u.push_back(u_new);
        is_active[static_cast<std::size_t>(p)] = 1;
        break;
      }
      drop(l);  // a partial step: row l leaves, then try row p again
    }
  }
  out.x = x;
  out.objective = f;
  out.status = Status::kNotConverged;
  return out;
}

}  // namespace freeturn
