#include "freeturn/nurbs/gauss_legendre.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

#include "freeturn/core/error.hpp"

namespace freeturn::nurbs {
namespace {

struct Rule {
  std::vector<double> nodes, weights;
};

Rule compute(int n) {
  Rule r;
  r.nodes.resize(static_cast<std::size_t>(n));
  r.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Tricomi's initial guess for the i-th root, then Newton on P_n.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {  // recurrence k P_k = (2k−1) x P_{k−1} − (k−1) P_{k−2}
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (x * p0 - p1) / (x * x - 1.0);
      const double dx = p0 / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    r.nodes[i] = -x;
    r.nodes[n - 1 - i] = x;
    r.weights[i] = r.weights[n - 1 - i] = w;
  }
  return r;
}

}  // namespace

QuadratureRule gauss_legendre(int n) {
  if (n < 1 || n > 64) throw InputError("quadrature order", "must be 1 to 64");
  static std::array<Rule, 65> rules;
  static std::array<std::once_flag, 65> once;
  std::call_once(once[n], [n] { rules[n] = compute(n); });
  return {rules[n].nodes, rules[n].weights};
}

}  // namespace freeturn::nurbs
