#include "freeturn/nurbs/basis.hpp"

#include <algorithm>

#include "freeturn/nurbs/scratch_buffer.hpp"

namespace freeturn::nurbs {

void basis_functions(int span, double u, int degree, const double* knots, double* out) {
  // A2.2: the triangular scheme of Cox–de Boor, with left[j] = u − u_{i+1−j} and
  // right[j] = u_{i+j} − u.
  ScratchBuffer<64> work(2 * (static_cast<std::size_t>(degree) + 1));
  double* left = work.data();
  double* right = left + degree + 1;
  out[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    double saved = 0.0;
    for (int k = 0; k < j; ++k) {
      const double temp = out[k] / (right[k + 1] + left[j - k]);
      out[k] = saved + right[k + 1] * temp;
      saved = left[j - k] * temp;
    }
    out[j] = saved;
  }
}

void basis_function_derivatives(int span, double u, int degree, int n, const double* knots,
                                double* ders, double* work) {
  // A2.3. ndu holds the basis functions (upper triangle) and the knot differences
  // (lower triangle); a holds two rows of the coefficients a_{k,j}, alternately.
  const int p = degree;
  const int q = p + 1;
  double* ndu = work;          // q × q
  double* left = ndu + q * q;  // q
  double* right = left + q;    // q
  double* a = right + q;       // 2 × q
  auto NDU = [&](int r, int c) -> double& { return ndu[r * q + c]; };
  auto A = [&](int r, int c) -> double& { return a[r * q + c]; };
  auto D = [&](int k, int j) -> double& { return ders[k * q + j]; };

  NDU(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - knots[span + 1 - j];
    right[j] = knots[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      NDU(j, r) = right[r + 1] + left[j - r];
      const double temp = NDU(r, j - 1) / NDU(j, r);
      NDU(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    NDU(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) D(0, j) = NDU(j, p);
  // Derivatives of order above p vanish.
  for (int k = p + 1; k <= n; ++k)
    for (int j = 0; j <= p; ++j) D(k, j) = 0.0;
  const int nk = std::min(n, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    A(0, 0) = 1.0;
    for (int k = 1; k <= nk; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        A(s2, 0) = A(s1, 0) / NDU(pk + 1, rk);
        d = A(s2, 0) * NDU(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        A(s2, j) = (A(s1, j) - A(s1, j - 1)) / NDU(pk + 1, rk + j);
        d += A(s2, j) * NDU(rk + j, pk);
      }
      if (r <= pk) {
        A(s2, k) = -A(s1, k - 1) / NDU(pk + 1, r);
        d += A(s2, k) * NDU(r, pk);
      }
      D(k, r) = d;
      std::swap(s1, s2);
    }
  }
  // Multiply through by p!/(p−k)!.
  double factor = p;
  for (int k = 1; k <= nk; ++k) {
    for (int j = 0; j <= p; ++j) D(k, j) *= factor;
    factor *= (p - k);
  }
}

}  // namespace freeturn::nurbs
