#include "freeturn/nurbs/curve.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/scratch_buffer.hpp"

namespace freeturn::nurbs {

double binomial(int n, int k) {
  // Pascal's triangle up to n = 16 (the derivative orders that occur), by recurrence.
  static const auto table = [] {
    std::array<std::array<double, 17>, 17> t{};
    for (int i = 0; i <= 16; ++i) {
      t[i][0] = t[i][i] = 1.0;
      for (int j = 1; j < i; ++j) t[i][j] = t[i - 1][j - 1] + t[i - 1][j];
    }
    return t;
  }();
  if (n <= 16) return table[n][k];
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

namespace {

std::vector<Vector4d> to_homogeneous(const std::vector<Vector3d>& points,
                                     const std::vector<double>& weights) {
  if (!weights.empty() && weights.size() != points.size())
    throw InputError("weights", std::to_string(weights.size()) + " weights for " +
                                    std::to_string(points.size()) + " control points");
  std::vector<Vector4d> pw(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!(std::isfinite(w) && w > 0))
      throw InputError("weight " + std::to_string(i),
                       "must be a finite number greater than 0, not " + shortest_text(w));
    pw[i] << w * points[i], w;
  }
  return pw;
}

}  // namespace

NurbsCurve::NurbsCurve(int degree, std::vector<double> knots, const std::vector<Vector3d>& points,
                       const std::vector<double>& weights)
    : NurbsCurve(KnotVector(degree, std::move(knots)), to_homogeneous(points, weights)) {}

NurbsCurve::NurbsCurve(KnotVector knots, std::vector<Vector4d> homogeneous_points)
    : knots_(std::move(knots)), points_(std::move(homogeneous_points)) {
  validate_points();
  rational_ = std::any_of(points_.begin(), points_.end(),
                          [&](const Vector4d& p) { return p.w() != points_[0].w(); });
}

void NurbsCurve::validate_points() const {
  if (static_cast<int>(points_.size()) != knots_.count())
    throw InputError("control points",
                     std::to_string(points_.size()) + " control points, but degree " +
                         std::to_string(knots_.degree()) + " and " + std::to_string(knots_.size()) +
                         " knots need " + std::to_string(knots_.count()));
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!points_[i].allFinite())
      throw InputError("control point " + std::to_string(i), "has a coordinate that is not finite");
    if (!(points_[i].w() > 0))
      throw InputError("weight " + std::to_string(i), "must be greater than 0");
  }
}

void NurbsCurve::derivatives(double u, int n, Vector3d* out) const {
  const int p = degree();
  u = std::clamp(u, front(), back());
  const int span = knots_.find_span(u);
  const std::size_t q = static_cast<std::size_t>(p) + 1;
  const std::size_t rows = static_cast<std::size_t>(n) + 1;
  ScratchBuffer<256> buf(rows * q + basis_derivatives_work_size(p));
  double* ders = buf.data();
  basis_function_derivatives(span, u, p, n, knots_.knots().data(), ders, ders + rows * q);
  // A3.2 on the homogeneous points gives A^(k) and w^(k); then A4.2:
  // C^(k) = (A^(k) − Σ_{i=1..k} C(k,i) w^(i) C^(k−i)) / w. Only the weights' derivatives
  // need keeping; each A^(k) is used as soon as it is made.
  ScratchBuffer<16> w(rows);
  for (int k = 0; k <= n; ++k) {
    Vector4d a = Vector4d::Zero();
    for (int j = 0; j <= p; ++j) a += ders[k * (p + 1) + j] * points_[span - p + j];
    w[k] = a.w();
    Vector3d v = a.head<3>();
    for (int i = 1; i <= k; ++i) v -= binomial(k, i) * w[i] * out[k - i];
    out[k] = v / w[0];
  }
}

Vector3d NurbsCurve::point(double u) const {
  const int p = degree();
  u = std::clamp(u, front(), back());
  const int span = knots_.find_span(u);
  ScratchBuffer<32> n(static_cast<std::size_t>(p) + 1);
  basis_functions(span, u, p, knots_.knots().data(), n.data());
  Vector4d s = Vector4d::Zero();
  for (int j = 0; j <= p; ++j) s += n[j] * points_[span - p + j];
  return s.head<3>() / s.w();
}

CurveDerivatives NurbsCurve::evaluate(double u, int order) const {
  order = std::clamp(order, 0, 2);
  Vector3d d[3] = {Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
  derivatives(u, order, d);
  return {d[0], d[1], d[2]};
}

double NurbsCurve::curvature(double u) const {
  const CurveDerivatives c = evaluate(u, 2);
  const double speed = c.d1.norm();
  return c.d1.cross(c.d2).norm() / (speed * speed * speed);
}

NurbsCurve NurbsCurve::insert_knot(double u, int times) const {
  // A5.1 on the homogeneous points.
  const int p = degree();
  if (!(u >= front() && u <= back()))
    throw InputError("knot insertion", "u = " + shortest_text(u) + " is outside the domain");
  const int s = knots_.multiplicity(u);
  if (times <= 0) return *this;
  if (s + times > p)
    throw InputError("knot insertion", "u = " + shortest_text(u) + " would have multiplicity " +
                                           std::to_string(s + times) + " above the degree " +
                                           std::to_string(p));
  const int k = knots_.find_span(u);
  const int np = count() - 1;
  const int r = times;
  const auto& UP = knots_.knots();
  std::vector<double> UQ(UP.size() + static_cast<std::size_t>(r));
  for (int i = 0; i <= k; ++i) UQ[i] = UP[i];
  for (int i = 1; i <= r; ++i) UQ[k + i] = u;
  for (int i = k + 1; i < static_cast<int>(UP.size()); ++i) UQ[i + r] = UP[i];
  std::vector<Vector4d> Q(points_.size() + static_cast<std::size_t>(r));
  for (int i = 0; i <= k - p; ++i) Q[i] = points_[i];
  for (int i = k - s; i <= np; ++i) Q[i + r] = points_[i];
  std::vector<Vector4d> R(static_cast<std::size_t>(p - s) + 1);
  for (int i = 0; i <= p - s; ++i) R[i] = points_[k - p + i];
  int L = 0;
  for (int j = 1; j <= r; ++j) {
    L = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (u - UP[L + i]) / (UP[i + k + 1] - UP[L + i]);
      R[i] = alpha * R[i + 1] + (1.0 - alpha) * R[i];
    }
    Q[L] = R[0];
    Q[k + r - j - s] = R[p - j - s];
  }
  for (int i = L + 1; i < k - s; ++i) Q[i] = R[i - L];
  return NurbsCurve(KnotVector(p, std::move(UQ)), std::move(Q));
}

bool NurbsCurve::is_closed(double tolerance) const {
  return (point(front()) - point(back())).norm() <= tolerance;
}

}  // namespace freeturn::nurbs
