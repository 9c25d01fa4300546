#include "freeturn/nurbs/surface_span_cache.hpp"

#include <algorithm>

#include "freeturn/nurbs/basis.hpp"
#include "rational_derivatives.hpp"

namespace freeturn::nurbs {
namespace {

// The span holding t, as KnotVector::find_span decides it, when `span` is already it.
bool holds(const KnotVector& k, int span, double t) {
  const auto u = k.knots();
  if (span < 0) return false;
  const double lo = u[static_cast<std::size_t>(span)], hi = u[static_cast<std::size_t>(span) + 1];
  return t >= lo && (t < hi || (t == k.back() && span == k.count() - 1));
}

}  // namespace

SurfaceSpanCache::SurfaceSpanCache(const NurbsSurface& surface) : surface_(surface) {
  const std::size_t pu = static_cast<std::size_t>(surface.degree_u()) + 1;
  const std::size_t qv = static_cast<std::size_t>(surface.degree_v()) + 1;
  spans_.resize(kSpans);
  coefficients_.resize(kSpans * pu * qv);
  partial_.resize(pu * qv);
  const int p = std::max(surface.degree_u(), surface.degree_v());
  work_.resize((static_cast<std::size_t>(p) + 1) * (static_cast<std::size_t>(p) + 1) +
               basis_derivatives_work_size(p));
}

Vector4d* SurfaceSpanCache::coefficients(int slot) {
  const std::size_t size = static_cast<std::size_t>(surface_.degree_u() + 1) *
                           static_cast<std::size_t>(surface_.degree_v() + 1);
  return coefficients_.data() + static_cast<std::size_t>(slot) * size;
}

void SurfaceSpanCache::enter(int slot, int span_u, int span_v) {
  const NurbsSurface& s = surface_;
  const int p = s.degree_u(), q = s.degree_v();
  const int pu = p + 1, qv = q + 1;
  Span& span = spans_[static_cast<std::size_t>(slot)];
  span.span_u = span_u;
  span.span_v = span_v;
  span.u0 = s.knots_u().knots()[static_cast<std::size_t>(span_u)];
  span.v0 = s.knots_v().knots()[static_cast<std::size_t>(span_v)];
  const double u0 = span.u0, v0 = span.v0;
  Vector4d* const a = coefficients(slot);
  double* ders = work_.data();
  double* scratch = ders + (std::max(p, q) + 1) * (std::max(p, q) + 1);
  // Σ_r c_rk P^w_rs: the u-direction's Taylor coefficients (k-th derivative over k!).
  basis_function_derivatives(span_u, u0, p, p, s.knots_u().knots().data(), ders, scratch);
  const int nvc = s.count_v();
  const Vector4d* base = &s.homogeneous_points()[static_cast<std::size_t>((span_u - p) * nvc + span_v - q)];
  double factorial = 1;
  for (int k = 0; k <= p; ++k) {
    if (k > 0) factorial *= k;
    for (int c = 0; c < qv; ++c) {
      Vector4d t = Vector4d::Zero();
      for (int r = 0; r < pu; ++r) t += (ders[k * pu + r] / factorial) * base[r * nvc + c];
      partial_[static_cast<std::size_t>(k * qv + c)] = t;
    }
  }
  // a_kl = Σ_s d_sl (Σ_r c_rk P^w_rs).
  basis_function_derivatives(span_v, v0, q, q, s.knots_v().knots().data(), ders, scratch);
  for (int k = 0; k < pu; ++k) {
    double fl = 1;
    for (int l = 0; l <= q; ++l) {
      if (l > 0) fl *= l;
      Vector4d t = Vector4d::Zero();
      for (int c = 0; c < qv; ++c)
        t += (ders[l * qv + c] / fl) * partial_[static_cast<std::size_t>(k * qv + c)];
      a[static_cast<std::size_t>(k * qv + l)] = t;
    }
  }
}

namespace {

// The homogeneous partials aw[k][l] (k + l ≤ kOrder) at (du, dv) from the power form a
// ((p + 1) × (q + 1), a_kl at k·(q + 1) + l): Horner in v for each power of u (B_k and
// its v-derivatives), then in u. Only the chains the order needs are run: a path's
// point and first partials skip the three second-order ones.
template <int kOrder>
void power_form_partials(const Vector4d* a, int p, int q, double du, double dv,
                         Vector4d (&aw)[3][3]) {
  const int qv = q + 1;
  for (auto& row : aw)
    for (Vector4d& x : row) x.setZero();
  for (int k = p; k >= 0; --k) {
    const Vector4d* row = a + k * qv;
    Vector4d b = row[q], b1 = Vector4d::Zero(), b2 = Vector4d::Zero();
    for (int l = q - 1; l >= 0; --l) {
      if constexpr (kOrder >= 2) b2 = b2 * dv + 2 * b1;
      if constexpr (kOrder >= 1) b1 = b1 * dv + b;
      b = b * dv + row[l];
    }
    if constexpr (kOrder >= 2) {
      aw[2][0] = aw[2][0] * du + 2 * aw[1][0];
      aw[1][1] = aw[1][1] * du + aw[0][1];
    }
    if constexpr (kOrder >= 1) aw[1][0] = aw[1][0] * du + aw[0][0];
    aw[0][0] = aw[0][0] * du + b;
    if constexpr (kOrder >= 1) aw[0][1] = aw[0][1] * du + b1;
    if constexpr (kOrder >= 2) aw[0][2] = aw[0][2] * du + b2;
  }
}

}  // namespace

SurfaceDerivatives SurfaceSpanCache::evaluate(double u, double v, int order) {
  const NurbsSurface& s = surface_;
  const int d = std::clamp(order, 0, 2);
  u = std::clamp(u, s.front_u(), s.back_u());
  v = std::clamp(v, s.front_v(), s.back_v());
  // The span the last evaluation used; else the slot (u, v)'s span hashes to, entered there
  // if it holds another.
  if (!holds(s.knots_u(), last_.span_u, u) || !holds(s.knots_v(), last_.span_v, v)) {
    const int span_u = s.knots_u().find_span(u), span_v = s.knots_v().find_span(v);
    const int slot = (span_u * 31 + span_v) & (kSpans - 1);
    const Span& held = spans_[static_cast<std::size_t>(slot)];
    if (held.span_u != span_u || held.span_v != span_v) enter(slot, span_u, span_v);
    last_ = held;
    last_coefficients_ = coefficients(slot);
  }
  const Span& span = last_;
  const Vector4d* const a = last_coefficients_;
  const int p = s.degree_u(), q = s.degree_v();
  const double du = u - span.u0, dv = v - span.v0;
  Vector4d aw[3][3];
  if (d == 0)
    power_form_partials<0>(a, p, q, du, dv, aw);
  else if (d == 1)
    power_form_partials<1>(a, p, q, du, dv, aw);
  else
    power_form_partials<2>(a, p, q, du, dv, aw);
  return rational_surface_derivatives(aw, d);
}

}  // namespace freeturn::nurbs
