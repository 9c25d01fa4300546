#pragma once
// A NURBS surface evaluated at consecutive points of a path, which stay in one knot span
// for many calls. On entering a span, its homogeneous patch is converted to power form
// about the span's corner (u₀, v₀):
//
//   S^w(u, v) = Σ_k Σ_l a_kl (u − u₀)^k (v − v₀)^l,   a_kl = Σ_r Σ_s c_rk d_sl P^w_rs,
//
// with c_rk = N_r^(k)(u₀)/k! the Taylor coefficients of the span's basis functions (exact:
// they are polynomials of degree p there; The NURBS Book, A2.3 for the derivatives), and
// likewise d_sl in v. Then S^w and its partials are a two-dimensional Horner scheme, and
// S, Su, Sv (and the second partials) follow by the quotient rule (A4.4). A path that leaves
// the spans held pays one conversion, (p+1)²(q+1)² products.
//
// The answer is a function of (u, v) alone (the span's coefficients are fixed by the span),
// so a cache used on any thread, in any order, gives the same bits; they agree with
// NurbsSurface::evaluate to rounding.
//
// It holds up to kSpans spans, not one, each in the slot its span indices hash to: a nose's
// searches about a contact reach a nose radius either side, across several spans of a fine
// grid, and the cut's simulation scans rows across the whole surface; a cache of one span
// converted one again at most steps (a quarter of a height grid's run).

#include <vector>

#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

class SurfaceSpanCache {
 public:
  // `surface` must outlive the cache.
  explicit SurfaceSpanCache(const NurbsSurface& surface);
  // Not copied: it points into its own storage (a thread keeps one in place).
  SurfaceSpanCache(const SurfaceSpanCache&) = delete;
  SurfaceSpanCache& operator=(const SurfaceSpanCache&) = delete;

  // S and its partials up to `order` (0, 1 or 2) at (u, v), clamped to the domain.
  SurfaceDerivatives evaluate(double u, double v, int order = 1);

  const NurbsSurface& surface() const { return surface_; }

 private:
  static constexpr int kSpans = 64;  // a power of two (the slot is a hash's low bits)
  // One span held: which, and its corner; its power form is the slot's part of
  // coefficients_.
  struct Span {
    int span_u = -1, span_v = -1;
    double u0 = 0, v0 = 0;
  };
  // The power form of slot k's span: (p + 1) × (q + 1), a_kl at k·(q + 1) + l.
  Vector4d* coefficients(int slot);
  void enter(int slot, int span_u, int span_v);

  const NurbsSurface& surface_;
  // On the heap, not in the object: a thread's cache lives in thread-local storage, which
  // a library loaded by dlopen (the Python module) must keep small.
  std::vector<Span> spans_;
  // Every slot's power form in one allocation (a thread that alternates between two
  // surfaces builds its cache again at each switch).
  std::vector<Vector4d> coefficients_;
  // The span the last evaluation used, tried first (a copy, so that a path that stays in
  // it reads what a cache of one span read), and its power form.
  Span last_;
  const Vector4d* last_coefficients_ = nullptr;
  std::vector<double> work_;      // basis derivatives and their scratch
  std::vector<Vector4d> partial_; // (p + 1) × (q + 1): Σ_r c_rk P^w_rs, at k·(q + 1) + s
};

}  // namespace freeturn::nurbs
