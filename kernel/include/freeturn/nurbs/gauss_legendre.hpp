#pragma once
// Gauss–Legendre quadrature rules on [−1, 1], computed once per order by Newton's method
// on the Legendre polynomial (Numerical Recipes §4.6 "gauleg"; Golub–Welsch would need an
// eigen-solver for the same nodes).

#include <span>

namespace freeturn::nurbs {

struct QuadratureRule {
  std::span<const double> nodes;    // ascending, in (−1, 1)
  std::span<const double> weights;  // sum to 2
};

// The n-point rule, 1 ≤ n ≤ 64; exact for polynomials of degree 2n − 1. Thread-safe.
QuadratureRule gauss_legendre(int n);

}  // namespace freeturn::nurbs
