#include "freeturn/nurbs/surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/scratch_buffer.hpp"
#include "rational_derivatives.hpp"

namespace freeturn::nurbs {
namespace {

std::string net_index(int k, int count_v) {
  return std::to_string(k / count_v) + "," + std::to_string(k % count_v);
}

// A knot vector whose errors say which direction they belong to.
KnotVector knots_in(const char* direction, int degree, const std::vector<double>& knots) {
  try {
    return KnotVector(degree, knots);
  } catch (const InputError& e) {
    throw InputError(std::string(direction) + " " + e.where(), e.problem());
  }
}

std::vector<Vector4d> homogeneous_net(const std::vector<Vector3d>& points,
                                      const std::vector<double>& weights, int count_v) {
  if (!weights.empty() && weights.size() != points.size())
    throw InputError("weights", std::to_string(weights.size()) + " weights for " +
                                    std::to_string(points.size()) + " control points");
  count_v = std::max(count_v, 1);
  std::vector<Vector4d> net(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double w = weights.empty() ? 1.0 : weights[k];
    if (!(std::isfinite(w) && w > 0))
      throw InputError("weight " + net_index(static_cast<int>(k), count_v),
                       "must be a finite number greater than 0, not " + shortest_text(w));
    net[k] << w * points[k], w;
  }
  return net;
}

}  // namespace

NurbsSurface::NurbsSurface(int degree_u, int degree_v, const std::vector<double>& knots_u,
                           const std::vector<double>& knots_v, const std::vector<Vector3d>& points,
                           const std::vector<double>& weights)
    : NurbsSurface(
          knots_in("u", degree_u, knots_u), knots_in("v", degree_v, knots_v),
          homogeneous_net(points, weights, static_cast<int>(knots_v.size()) - degree_v - 1)) {}

NurbsSurface::NurbsSurface(KnotVector knots_u, KnotVector knots_v,
                           std::vector<Vector4d> homogeneous_points)
    : knots_u_(std::move(knots_u)),
      knots_v_(std::move(knots_v)),
      points_(std::move(homogeneous_points)) {
  const std::size_t expected = static_cast<std::size_t>(count_u()) * count_v();
  if (points_.size() != expected)
    throw InputError("control points", std::to_string(points_.size()) +
                                           " control points, but the knot vectors need " +
                                           std::to_string(expected));
  for (std::size_t k = 0; k < expected; ++k) {
    if (!points_[k].allFinite())
      throw InputError("control point " + net_index(static_cast<int>(k), count_v()),
                       "has a coordinate that is not finite");
    if (!(points_[k].w() > 0))
      throw InputError("weight " + net_index(static_cast<int>(k), count_v()),
                       "must be greater than 0");
  }
  rational_ = std::any_of(points_.begin(), points_.end(),
                          [&](const Vector4d& p) { return p.w() != points_[0].w(); });
}

Vector3d NurbsSurface::point(double u, double v) const {
  const int p = degree_u(), q = degree_v();
  u = std::clamp(u, front_u(), back_u());
  v = std::clamp(v, front_v(), back_v());
  const int su = knots_u_.find_span(u), sv = knots_v_.find_span(v);
  ScratchBuffer<64> buf(static_cast<std::size_t>(p + q + 2));
  double* nu = buf.data();
  double* nv = nu + p + 1;
  basis_functions(su, u, p, knots_u_.knots().data(), nu);
  basis_functions(sv, v, q, knots_v_.knots().data(), nv);
  const int nvc = count_v();
  Vector4d s = Vector4d::Zero();
  for (int r = 0; r <= p; ++r) {
    const Vector4d* row = &points_[(su - p + r) * nvc + sv - q];
    Vector4d t = Vector4d::Zero();
    for (int c = 0; c <= q; ++c) t += nv[c] * row[c];
    s += nu[r] * t;
  }
  return s.head<3>() / s.w();
}

SurfaceDerivatives NurbsSurface::evaluate(double u, double v, int order) const {
  const int d = std::clamp(order, 0, 2);
  const int p = degree_u(), q = degree_v();
  u = std::clamp(u, front_u(), back_u());
  v = std::clamp(v, front_v(), back_v());
  const int span_u = knots_u_.find_span(u), span_v = knots_v_.find_span(v);
  const std::size_t pu = static_cast<std::size_t>(p) + 1, qv = static_cast<std::size_t>(q) + 1;
  const std::size_t rows = static_cast<std::size_t>(d) + 1;
  const std::size_t work = std::max(basis_derivatives_work_size(p), basis_derivatives_work_size(q));
  ScratchBuffer<256> buf(rows * (pu + qv) + work);
  double* nu = buf.data();      // rows × (p + 1)
  double* nv = nu + rows * pu;  // rows × (q + 1)
  double* scratch = nv + rows * qv;
  basis_function_derivatives(span_u, u, p, d, knots_u_.knots().data(), nu, scratch);
  basis_function_derivatives(span_v, v, q, d, knots_v_.knots().data(), nv, scratch);

  // A3.6 on P^w: for each u-derivative order k, temp_s = Σ_r N^(k)_r P^w_{r,s}, then
  // A^(k,l) = Σ_s N^(l)_s temp_s. aw[k][l] for k + l ≤ d.
  Vector4d aw[3][3];
  const int nvc = count_v();
  const Vector4d* base = &points_[(span_u - p) * nvc + span_v - q];
  for (int k = 0; k <= d; ++k) {
    for (int l = 0; l <= d - k; ++l) aw[k][l].setZero();
    for (int s = 0; s <= q; ++s) {
      Vector4d t = Vector4d::Zero();
      for (int r = 0; r <= p; ++r) t += nu[k * static_cast<int>(pu) + r] * base[r * nvc + s];
      for (int l = 0; l <= d - k; ++l) aw[k][l] += nv[l * static_cast<int>(qv) + s] * t;
    }
  }
  return rational_surface_derivatives(aw, d);
}

Vector3d NurbsSurface::normal(double u, double v) const {
  const SurfaceDerivatives d = evaluate(u, v, 2);
  Vector3d n = d.su.cross(d.sv);
  const double scale = d.su.squaredNorm() + d.sv.squaredNorm();
  if (n.squaredNorm() <= 1e-24 * scale * scale) {
    // A degenerate edge (a pole): one partial vanishes along the whole edge. Near it,
    // Sv ≈ (u − u_edge)·Suv (or Su ≈ (v − v_edge)·Suv), so the limit of Su × Sv from
    // inside the domain points along ±Su × Suv (or ±Suv × Sv).
    const bool sv_vanishes = d.sv.squaredNorm() < d.su.squaredNorm();
    if (sv_vanishes) {
      const double side = u >= back_u() ? -1.0 : 1.0;
      n = side * d.su.cross(d.suv);
    } else {
      const double side = v >= back_v() ? -1.0 : 1.0;
      n = side * d.suv.cross(d.sv);
    }
  }
  const double len = n.norm();
  return len > 0 ? Vector3d(n / len) : Vector3d::Zero();
}

NurbsCurve NurbsSurface::curve_at_v(double v) const {
  // Each column j contributes through N_j(v): the u-curve's points are Σ_j N_j(v) P^w_{i,j}.
  const int q = degree_v();
  v = std::clamp(v, front_v(), back_v());
  const int span = knots_v_.find_span(v);
  ScratchBuffer<32> n(static_cast<std::size_t>(q) + 1);
  basis_functions(span, v, q, knots_v_.knots().data(), n.data());
  std::vector<Vector4d> pts(static_cast<std::size_t>(count_u()));
  for (int i = 0; i < count_u(); ++i) {
    Vector4d s = Vector4d::Zero();
    for (int c = 0; c <= q; ++c) s += n[c] * homogeneous_point(i, span - q + c);
    pts[i] = s;
  }
  return NurbsCurve(knots_u_, std::move(pts));
}

NurbsCurve NurbsSurface::curve_at_u(double u) const {
  const int p = degree_u();
  u = std::clamp(u, front_u(), back_u());
  const int span = knots_u_.find_span(u);
  ScratchBuffer<32> n(static_cast<std::size_t>(p) + 1);
  basis_functions(span, u, p, knots_u_.knots().data(), n.data());
  std::vector<Vector4d> pts(static_cast<std::size_t>(count_v()));
  for (int j = 0; j < count_v(); ++j) {
    Vector4d s = Vector4d::Zero();
    for (int r = 0; r <= p; ++r) s += n[r] * homogeneous_point(span - p + r, j);
    pts[j] = s;
  }
  return NurbsCurve(knots_v_, std::move(pts));
}

NurbsSurface NurbsSurface::insert_knot_u(double u, int times) const {
  // Knot insertion is linear in the control points, so each column of the net (fixed j)
  // is refined as a curve in u with the same knots.
  std::vector<Vector4d> out;
  KnotVector knots;
  const int nu = count_u(), nv = count_v();
  for (int j = 0; j < nv; ++j) {
    std::vector<Vector4d> column(static_cast<std::size_t>(nu));
    for (int i = 0; i < nu; ++i) column[i] = homogeneous_point(i, j);
    const NurbsCurve refined = NurbsCurve(knots_u_, std::move(column)).insert_knot(u, times);
    if (j == 0) {
      knots = refined.knots();
      out.resize(static_cast<std::size_t>(refined.count()) * nv);
    }
    for (int i = 0; i < refined.count(); ++i) out[i * nv + j] = refined.homogeneous_points()[i];
  }
  return NurbsSurface(std::move(knots), knots_v_, std::move(out));
}

NurbsSurface NurbsSurface::insert_knot_v(double v, int times) const {
  std::vector<Vector4d> out;
  KnotVector knots;
  const int nu = count_u(), nv = count_v();
  int new_nv = 0;
  for (int i = 0; i < nu; ++i) {
    std::vector<Vector4d> row(points_.begin() + i * nv, points_.begin() + (i + 1) * nv);
    const NurbsCurve refined = NurbsCurve(knots_v_, std::move(row)).insert_knot(v, times);
    if (i == 0) {
      knots = refined.knots();
      new_nv = refined.count();
      out.resize(static_cast<std::size_t>(nu) * new_nv);
    }
    std::copy(refined.homogeneous_points().begin(), refined.homogeneous_points().end(),
              out.begin() + i * new_nv);
  }
  return NurbsSurface(knots_u_, std::move(knots), std::move(out));
}

}  // namespace freeturn::nurbs
