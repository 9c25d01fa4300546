#include "collocation.hpp"

#include <algorithm>

#include "freeturn/nurbs/basis.hpp"

namespace freeturn::nurbs {

SparseMatrix collocation_matrix(const KnotVector& knots, const std::vector<double>& params) {
  const int p = knots.degree();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(params.size() * static_cast<std::size_t>(p + 1));
  std::vector<double> n(static_cast<std::size_t>(p + 1));
  int span = p;
  for (std::size_t k = 0; k < params.size(); ++k) {
    const double u = std::clamp(params[k], knots.front(), knots.back());
    span = knots.find_span(u, span);
    basis_functions(span, u, p, knots.knots().data(), n.data());
    for (int j = 0; j <= p; ++j)
      if (n[j] != 0) t.emplace_back(static_cast<int>(k), span - p + j, n[j]);
  }
  SparseMatrix m(static_cast<int>(params.size()), knots.count());
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

}  // namespace freeturn::nurbs

#include "freeturn/nurbs/gauss_legendre.hpp"
#include "freeturn/nurbs/scratch_buffer.hpp"

namespace freeturn::nurbs {

SparseMatrix derivative_gram_matrix(const KnotVector& knots, int k) {
  const int p = knots.degree();
  const QuadratureRule rule = gauss_legendre(p + 1);
  const std::vector<double> b = knots.breakpoints();
  const std::size_t q = static_cast<std::size_t>(p) + 1;
  std::vector<double> ders((static_cast<std::size_t>(k) + 1) * q);
  std::vector<double> work(basis_derivatives_work_size(p));
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t s = 0; s + 1 < b.size(); ++s) {
    const double half = 0.5 * (b[s + 1] - b[s]), mid = 0.5 * (b[s + 1] + b[s]);
    for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
      const double u = mid + half * rule.nodes[g];
      const int span = knots.find_span(u);
      basis_function_derivatives(span, u, p, k, knots.knots().data(), ders.data(), work.data());
      const double* row = ders.data() + static_cast<std::size_t>(k) * q;
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= p; ++j)
          t.emplace_back(span - p + i, span - p + j, rule.weights[g] * half * row[i] * row[j]);
    }
  }
  SparseMatrix m(knots.count(), knots.count());
  m.setFromTriplets(t.begin(), t.end());  // sums duplicates
  return m;
}

}  // namespace freeturn::nurbs
