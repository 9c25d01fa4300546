#pragma once
// B-spline basis functions and their derivatives (The NURBS Book, §2.5).

#include <cstddef>

namespace freeturn::nurbs {

// The p + 1 non-vanishing basis functions N_{span−p,p}(u) … N_{span,p}(u) (A2.2).
// knots: the full knot vector. out: p + 1 values.
void basis_functions(int span, double u, int degree, const double* knots, double* out);

// Scratch doubles needed by basis_function_derivatives for a degree.
constexpr std::size_t basis_derivatives_work_size(int degree) {
  const std::size_t q = static_cast<std::size_t>(degree) + 1;
  return q * q + 4 * q;
}

// Derivatives 0…n of the p + 1 non-vanishing basis functions at u (A2.3).
// ders: (n + 1) × (p + 1), row k holds the k-th derivatives (row-major).
// work: basis_derivatives_work_size(p) doubles.
void basis_function_derivatives(int span, double u, int degree, int n, const double* knots,
                                double* ders, double* work);

}  // namespace freeturn::nurbs
