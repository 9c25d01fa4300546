#include "freeturn/surface/nurbs_height_field.hpp"

#include "freeturn/surface/crease_sink.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "freeturn/nurbs/surface_span_cache.hpp"

#include "freeturn/core/error.hpp"

namespace freeturn {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The last answer of this thread, per surface: consecutive queries of a path are close.
struct WarmStart {
  std::uint64_t owner = 0;  // the surface's instance id; 0: none
  double u = 0, v = 0;
};
thread_local WarmStart warm_start;

// This thread's span cache, for the surface with instance id `owner` (0: none yet).
struct ThreadSpanCache {
  std::uint64_t owner = 0;
  std::optional<nurbs::SurfaceSpanCache> cache;
};
thread_local ThreadSpanCache span_cache;

double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp(-a.dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d).norm();
}

}  // namespace

void forget_thread_warm_starts() { warm_start = {}; }

nurbs::SurfaceDerivatives NurbsHeightField::evaluate_cached(double u, double v, int order) const {
  if (span_cache.owner != id_.value) {
    span_cache.cache.emplace(locator_.surface());
    span_cache.owner = id_.value;
  }
  return span_cache.cache->evaluate(u, v, order);
}

NurbsHeightField::NurbsHeightField(nurbs::NurbsSurface surface) : locator_(std::move(surface)) {
  const nurbs::NurbsSurface& s = locator_.surface();
  double z_max = -std::numeric_limits<double>::infinity();
  Eigen::AlignedBox3d box;
  for (const nurbs::Vector4d& p : s.homogeneous_points()) {
    z_max = std::max(z_max, p.z() / p.w());
    box.extend(Eigen::Vector3d(p.head<3>() / p.w()));
  }
  scale_ = std::max(1.0, box.diagonal().norm());
  z_above_ = z_max + scale_;

  // Affine parameters: every control point's x (y) is an affine function of its Greville
  // abscissa in u (v), and the surface is not rational.
  if (!s.is_rational() && s.count_u() >= 2 && s.count_v() >= 2) {
    const double gu0 = s.knots_u().greville(0), gu1 = s.knots_u().greville(s.count_u() - 1);
    const double gv0 = s.knots_v().greville(0), gv1 = s.knots_v().greville(s.count_v() - 1);
    const Eigen::Vector3d p00 = s.control_point(0, 0);
    sx_ = (s.control_point(s.count_u() - 1, 0).x() - p00.x()) / (gu1 - gu0);
    sy_ = (s.control_point(0, s.count_v() - 1).y() - p00.y()) / (gv1 - gv0);
    x0_ = p00.x() - sx_ * gu0;
    y0_ = p00.y() - sy_ * gv0;
    affine_ = sx_ != 0 && sy_ != 0;
    for (int i = 0; affine_ && i < s.count_u(); ++i)
      for (int j = 0; affine_ && j < s.count_v(); ++j) {
        const Eigen::Vector3d p = s.control_point(i, j);
        affine_ = std::abs(p.x() - (x0_ + sx_ * s.knots_u().greville(i))) <= 1e-13 * scale_ &&
                  std::abs(p.y() - (y0_ + sy_ * s.knots_v().greville(j))) <= 1e-13 * scale_;
      }
  }

  if (affine_) bound_from_net();

  // A graph over x-y: the Jacobian of (S_x, S_y) keeps one sign away from poles.
  const int n = 8 * std::max(s.count_u(), s.count_v());
  int sign = 0;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      const double u = s.front_u() + (s.back_u() - s.front_u()) * a / n;
      const double v = s.front_v() + (s.back_v() - s.front_v()) * b / n;
      const nurbs::SurfaceDerivatives d = s.evaluate(u, v, 1);
      const double det = d.su.x() * d.sv.y() - d.su.y() * d.sv.x();
      if (std::abs(det) <= 1e-9 * d.su.norm() * d.sv.norm()) continue;  // pole or edge-on
      const int this_sign = det > 0 ? 1 : -1;
      if (sign == 0) sign = this_sign;
      if (this_sign != sign)
        throw InputError("surface",
                         "the NURBS surface is not a height field z = f(x, y): its projection "
                         "onto the x-y plane folds over near (u, v) = (" +
                             std::to_string(u) + ", " + std::to_string(v) + ")");
    }
  if (sign == 0)
    throw InputError("surface", "the NURBS surface is edge-on to the z axis everywhere");
  double u, v;
  defined_radius_ = parameters_at(0, 0, u, v) ? boundary_distance() : 0.0;
  find_creases();
}

namespace {

// The control values of a B-spline's k-th derivative from its (k − 1)-th's, c of degree
// p − k + 1 on the knots U shifted by k − 1 (Piegl & Tiller, Eq. 3.8, A3.3):
//   c⁽ᵏ⁾_i = (p − k + 1)/(U_{i+p+1} − U_{i+k}) · (c⁽ᵏ⁻¹⁾_{i+1} − c⁽ᵏ⁻¹⁾_i),
// 0 where the knots close up (that basis function is 0). `c` holds `rows` rows of `count`
// values along the direction differentiated, stored [i][row] (i·rows + row) along u and
// [row][i] (row·count + i) along v; the result keeps that layout, count − 1 values a row.
std::vector<double> derivative_net(const std::vector<double>& c, int count, int rows, bool along_u,
                                   const nurbs::KnotVector& knots, int k) {
  const int p = knots.degree(), out_count = count - 1;
  std::vector<double> out(static_cast<std::size_t>(out_count * rows));
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < out_count; ++i) {
      const auto at = [&](const std::vector<double>& net, int n, int index) {
        return along_u ? net[static_cast<std::size_t>(index * rows + r)]
                       : net[static_cast<std::size_t>(r * n + index)];
      };
      const double span = knots[i + p + 1] - knots[i + k];
      const double value =
          span > 0 ? (p - k + 1) * (at(c, count, i + 1) - at(c, count, i)) / span : 0.0;
      out[static_cast<std::size_t>(along_u ? i * rows + r : r * out_count + i)] = value;
    }
  return out;
}

}  // namespace

// z(x, y) = S_z(u, v) with u = (x − x0)/s_x, v = (y − y0)/s_y: the Hessian is
// [[S_uu/s_x², S_uv/(s_x s_y)], [S_uv/(s_x s_y), S_vv/s_y²]], and each of S_uu, S_uv, S_vv is a
// B-spline whose values lie within its control values (a convex combination in every
// span). Its largest eigenvalue is at most the larger diagonal bound plus |S_uv|'s
// (Gershgorin); the slope at most the two first derivatives' bounds combined.
void NurbsHeightField::bound_from_net() {
  const nurbs::NurbsSurface& s = locator_.surface();
  const int nu = s.count_u(), nv = s.count_v();
  std::vector<double> z(static_cast<std::size_t>(nu * nv));
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      z[static_cast<std::size_t>(i * nv + j)] = s.control_point(i, j).z();
  const auto largest = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
  };
  const auto largest_abs = [](const std::vector<double>& v) {
    double most = 0;
    for (const double x : v) most = std::max(most, std::abs(x));
    return most;
  };
  // Rows along u: the nu values of each of the nv columns; along v: nv values of nu rows.
  const std::vector<double> su = derivative_net(z, nu, nv, true, s.knots_u(), 1);
  const std::vector<double> sv = derivative_net(z, nv, nu, false, s.knots_v(), 1);
  const std::vector<double> suv = derivative_net(su, nv, nu - 1, false, s.knots_v(), 1);
  const double uu =
      s.degree_u() >= 2 ? largest(derivative_net(su, nu - 1, nv, true, s.knots_u(), 2)) : 0.0;
  const double vv =
      s.degree_v() >= 2 ? largest(derivative_net(sv, nv - 1, nu, false, s.knots_v(), 2)) : 0.0;
  const double bend =
      std::max(uu / (sx_ * sx_), vv / (sy_ * sy_)) + largest_abs(suv) / std::abs(sx_ * sy_);
  const double slope = std::hypot(largest_abs(su) / std::abs(sx_), largest_abs(sv) / std::abs(sy_));
  // The differences round by parts in 10¹⁶ of the net's values.
  if (std::isfinite(bend)) bend_bound_ = bend + 1e-12 * std::abs(bend);
  if (std::isfinite(slope)) slope_bound_ = slope * (1 + 1e-12);
}

void NurbsHeightField::find_creases() {
  const nurbs::NurbsSurface& s = locator_.surface();
  // A seam candidate is only C⁰ in parameter; it is a crease when the normals just either
  // side of it differ (sampled along the knot line) by more than rounding would explain.
  constexpr double kTurn = 1e-7;  // rad
  constexpr int kSamples = 16;
  const auto scan = [&](const nurbs::KnotVector& knots, bool along_u, std::vector<double>& out) {
    const std::vector<double> breaks = knots.breakpoints();
    const double span = knots.back() - knots.front();
    for (std::size_t k = 1; k + 1 < breaks.size(); ++k) {
      const double t = breaks[k];
      if (knots.multiplicity(t) < knots.degree()) continue;
      const double h = 1e-9 * span;
      const double lo = along_u ? s.front_v() : s.front_u(), hi = along_u ? s.back_v() : s.back_u();
      for (int j = 0; j <= kSamples; ++j) {
        const double w = lo + (hi - lo) * j / kSamples;
        const nurbs::Vector3d before = along_u ? s.normal(t - h, w) : s.normal(w, t - h);
        const nurbs::Vector3d after = along_u ? s.normal(t + h, w) : s.normal(w, t + h);
        if (before.allFinite() && after.allFinite() && before.cross(after).norm() > kTurn) {
          out.push_back(t);
          break;
        }
      }
    }
  };
  scan(s.knots_u(), true, crease_u_);
  scan(s.knots_v(), false, crease_v_);
}

int NurbsHeightField::section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                                      std::span<double> out) const {
  if (!has_creases() || !(rho_lo <= rho_hi) || !std::isfinite(rho_lo) || !std::isfinite(rho_hi))
    return 0;
  const double ct = line.cos, st = line.sin;
  CreaseSink found(out, rho_lo, rho_hi);
  const auto add = [&](double rho) {
    double u, v;
    if (!(rho >= rho_lo && rho <= rho_hi) || !parameters_at(rho * ct, rho * st, u, v)) return;
    found.add(rho);
  };
  if (affine_) {
    // x = x0 + sx·u: the knot line u = u* is the line x = x0 + sx·u*, met at ρ = x/cos θ.
    for (const double u : crease_u_)
      if (std::abs(ct) > 1e-15) add((x0_ + sx_ * u) / ct);
    for (const double v : crease_v_)
      if (std::abs(st) > 1e-15) add((y0_ + sy_ * v) / st);
  } else {
    // Along the section, u(ρ) − u* changes sign where it crosses the line u = u*.
    constexpr int kSteps = 16;
    double previous_rho = 0, previous_u = 0, previous_v = 0;
    bool has_previous = false;
    for (int i = 0; i <= kSteps; ++i) {
      const double rho = rho_lo + (rho_hi - rho_lo) * i / kSteps;
      double u, v;
      if (!parameters_at(rho * ct, rho * st, u, v)) {
        has_previous = false;
        continue;
      }
      if (has_previous) {
        const auto bisect = [&](double value, bool in_u) {
          const double a0 = (in_u ? previous_u : previous_v) - value, b0 = (in_u ? u : v) - value;
          // A closed direction wraps between samples: that is no crossing of its lines.
          const nurbs::KnotVector& knots =
              in_u ? locator_.surface().knots_u() : locator_.surface().knots_v();
          if (std::abs(b0 - a0) > 0.5 * (knots.back() - knots.front())) return;
          if (b0 == 0) {
            add(rho);
            return;
          }
          if (a0 == 0 || (a0 < 0) == (b0 < 0)) return;
          double lo = previous_rho, hi = rho, f_lo = a0;
          for (int it = 0; it < 60 && hi - lo > 1e-13 * std::max(1.0, std::abs(hi)); ++it) {
            const double mid = 0.5 * (lo + hi);
            double um, vm;
            if (!parameters_at(mid * ct, mid * st, um, vm)) return;
            const double f = (in_u ? um : vm) - value;
            if ((f < 0) == (f_lo < 0)) {
              lo = mid;
              f_lo = f;
            } else {
              hi = mid;
            }
          }
          add(0.5 * (lo + hi));
        };
        for (const double c : crease_u_) bisect(c, true);
        for (const double c : crease_v_) bisect(c, false);
      }
      previous_rho = rho;
      previous_u = u;
      previous_v = v;
      has_previous = true;
    }
  }
  return found.finish();
}

double NurbsHeightField::boundary_distance() const {
  const nurbs::NurbsSurface& s = locator_.surface();
  // Each edge as a fine polyline in x-y finds the basin of the edge's nearest point, and a
  // golden-section search on the edge itself then finds that point: the distance is the
  // edge's own (a polyline alone put a circular edge of radius 5 mm at 4.99992 mm, and
  // refused an aperture the data covers). An edge that collapses to a point (a pole) or is
  // a seam of a closed direction is not a boundary.
  const int n = 64 * std::max(s.count_u(), s.count_v());
  double best = std::numeric_limits<double>::infinity();
  for (int edge = 0; edge < 4; ++edge) {
    const bool along_v = edge < 2;  // u fixed
    if ((along_v && locator_.closed_u()) || (!along_v && locator_.closed_v())) continue;
    const double fixed = edge == 0   ? s.front_u()
                         : edge == 1 ? s.back_u()
                         : edge == 2 ? s.front_v()
                                     : s.back_v();
    const auto at = [&](double k) {  // k in [0, n] along the edge
      const double t = along_v ? s.front_v() + (s.back_v() - s.front_v()) * k / n
                               : s.front_u() + (s.back_u() - s.front_u()) * k / n;
      const nurbs::Vector3d p = along_v ? s.point(fixed, t) : s.point(t, fixed);
      return Eigen::Vector2d(p.x(), p.y());
    };
    double length = 0, polyline_best = std::numeric_limits<double>::infinity();
    int nearest = 0;
    Eigen::Vector2d previous = at(0);
    for (int k = 1; k <= n; ++k) {
      const Eigen::Vector2d p = at(k);
      length += (p - previous).norm();
      const double d = segment_distance(previous, p);
      if (d < polyline_best) polyline_best = d, nearest = k;
      previous = p;
    }
    if (!(length > 1e-9 * scale_)) continue;
    // The segment nearest the origin and its neighbours bracket the edge's nearest point.
    constexpr double kGolden = 0.6180339887498949;
    double lo = std::max(0, nearest - 2), hi = std::min(n, nearest + 1);
    const auto distance = [&](double k) { return at(k).norm(); };
    double edge_best = std::min(distance(lo), distance(hi));
    double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
    double f1 = distance(x1), f2 = distance(x2);
    for (int it = 0; it < 80 && hi - lo > 1e-13 * n; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - kGolden * (hi - lo), f1 = distance(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + kGolden * (hi - lo), f2 = distance(x2);
      }
    }
    edge_best = std::min({edge_best, f1, f2});
    best = std::min(best, edge_best);
  }
  return best;
}

bool NurbsHeightField::newton(double x, double y, double& u, double& v) const {
  const nurbs::NurbsSurface& s = locator_.surface();
  const double tolerance = 1e-13 * scale_;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 30; ++it) {
    const nurbs::SurfaceDerivatives d = evaluate_cached(u, v, 1);
    const Eigen::Vector2d r(d.point.x() - x, d.point.y() - y);
    const double residual = r.norm();
    if (residual <= tolerance) return true;
    // Stalled: rounding (the tolerance is below what S can resolve here) or outside.
    if (it > 3 && residual >= 0.5 * previous) return residual <= 1e-10 * scale_;
    previous = residual;
    Eigen::Matrix2d j;
    j << d.su.x(), d.sv.x(), d.su.y(), d.sv.y();
    Eigen::Vector2d step;
    const double det = j.determinant();
    if (std::abs(det) > 1e-12 * j.squaredNorm()) {
      step = j.partialPivLu().solve(-r);
    } else {  // at a pole: Levenberg–Marquardt
      const Eigen::Matrix2d a =
          j.transpose() * j + 1e-6 * j.squaredNorm() * Eigen::Matrix2d::Identity();
      step = a.ldlt().solve(-j.transpose() * r);
    }
    u += step.x();
    v += step.y();
    const auto wrap_or_clamp = [](double& t, double lo, double hi, bool closed) {
      if (closed) {
        t = lo + std::fmod(std::fmod(t - lo, hi - lo) + (hi - lo), hi - lo);
      } else {
        t = std::clamp(t, lo, hi);
      }
    };
    wrap_or_clamp(u, s.front_u(), s.back_u(), locator_.closed_u());
    wrap_or_clamp(v, s.front_v(), s.back_v(), locator_.closed_v());
  }
  return false;
}

bool NurbsHeightField::parameters_at(double x, double y, double& u, double& v) const {
  const nurbs::NurbsSurface& s = locator_.surface();
  if (affine_) {
    u = (x - x0_) / sx_;
    v = (y - y0_) / sy_;
    const double tu = 1e-12 * (s.back_u() - s.front_u()), tv = 1e-12 * (s.back_v() - s.front_v());
    if (!(u >= s.front_u() - tu && u <= s.back_u() + tu && v >= s.front_v() - tv &&
          v <= s.back_v() + tv))
      return false;
    u = std::clamp(u, s.front_u(), s.back_u());
    v = std::clamp(v, s.front_v(), s.back_v());
    return true;
  }
  if (warm_start.owner == id_.value) {
    u = warm_start.u;
    v = warm_start.v;
    if (newton(x, y, u, v)) {
      warm_start = {id_.value, u, v};
      return true;
    }
  }
  const nurbs::RayHit hit =
      locator_.intersect_ray(nurbs::Vector3d(x, y, z_above_), nurbs::Vector3d(0, 0, -1));
  if (hit.status != Status::kOk) return false;
  u = hit.u;
  v = hit.v;
  if (!newton(x, y, u, v)) return false;
  warm_start = {id_.value, u, v};
  return true;
}

HeightDerivatives NurbsHeightField::derivatives_at(double x, double y, double u, double v,
                                                   int order) const {
  const nurbs::NurbsSurface& s = locator_.surface();
  const nurbs::SurfaceDerivatives d = evaluate_cached(u, v, order);
  HeightDerivatives h;
  h.z = d.point.z();
  Eigen::Matrix2d j;
  j << d.su.x(), d.sv.x(), d.su.y(), d.sv.y();
  if (std::abs(j.determinant()) <= 1e-10 * j.squaredNorm()) {
    // A pole: the graph is smooth there even though the parameterisation is not.
    const nurbs::Vector3d n = s.normal(u, v);
    h.zx = -n.x() / n.z();
    h.zy = -n.y() / n.z();
    if (order >= 2) {
      const double step = 1e-4 * scale_;
      double zp, zm, gxp, gyp, gxm, gym;
      sag_gradient(x + step, y, zp, gxp, gyp);
      sag_gradient(x - step, y, zm, gxm, gym);
      h.zxx = (gxp - gxm) / (2 * step);
      const double zxy_from_x = (gyp - gym) / (2 * step);
      sag_gradient(x, y + step, zp, gxp, gyp);
      sag_gradient(x, y - step, zm, gxm, gym);
      h.zyy = (gyp - gym) / (2 * step);
      h.zxy = 0.5 * (zxy_from_x + (gxp - gxm) / (2 * step));
    }
    return h;
  }
  const Eigen::Matrix2d j_inv = j.inverse();
  const Eigen::Vector2d grad = j_inv.transpose() * Eigen::Vector2d(d.su.z(), d.sv.z());
  h.zx = grad.x();
  h.zy = grad.y();
  if (order >= 2) {
    Eigen::Matrix2d m;
    m << d.suu.z() - grad.x() * d.suu.x() - grad.y() * d.suu.y(),
        d.suv.z() - grad.x() * d.suv.x() - grad.y() * d.suv.y(), 0,
        d.svv.z() - grad.x() * d.svv.x() - grad.y() * d.svv.y();
    m(1, 0) = m(0, 1);
    const Eigen::Matrix2d hess = j_inv.transpose() * m * j_inv;
    h.zxx = hess(0, 0);
    h.zxy = 0.5 * (hess(0, 1) + hess(1, 0));
    h.zyy = hess(1, 1);
  }
  return h;
}

void NurbsHeightField::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  double u, v;
  if (!parameters_at(x, y, u, v)) {
    z = zx = zy = kNaN;
    return;
  }
  const HeightDerivatives h = derivatives_at(x, y, u, v, 1);
  z = h.z;
  zx = h.zx;
  zy = h.zy;
}

HeightDerivatives NurbsHeightField::height_derivatives(double x, double y) const {
  double u, v;
  if (!parameters_at(x, y, u, v)) return {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  return derivatives_at(x, y, u, v, 2);
}

}  // namespace freeturn
