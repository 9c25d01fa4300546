#pragma once
// Arc length of a NURBS curve and its inverse. Lengths come from adaptive Gauss–Legendre
// quadrature of |C'(u)| inside each knot span (where the speed is smooth), summed into a
// table at the breakpoints; the inverse s → u is Newton's method on L(u) − s with a
// bisection safeguard. Relative accuracy 1e-12 or better.

#include <vector>

#include "freeturn/nurbs/curve.hpp"

namespace freeturn::nurbs {

class ArcLengthTable {
 public:
  explicit ArcLengthTable(NurbsCurve curve);

  const NurbsCurve& curve() const { return curve_; }
  // Length of the whole curve.
  double total() const { return cumulative_.back(); }
  // Length from the start of the domain to u (u clamped to the domain).
  double length_to(double u) const;
  // Length between two parameters (negative if u1 < u0).
  double length(double u0, double u1) const { return length_to(u1) - length_to(u0); }
  // The parameter at arc length s from the start (s clamped to [0, total]).
  double parameter_at(double s) const;

 private:
  double integrate(double a, double b) const;  // ∫_a^b |C'| du inside one span

  NurbsCurve curve_;
  std::vector<double> breaks_;      // distinct knots in the domain
  std::vector<double> cumulative_;  // length to each breakpoint
};

}  // namespace freeturn::nurbs
