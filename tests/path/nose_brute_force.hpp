#pragma once
// The nose against a radial section by brute force, for the tests of the nose's
// placement (section_envelope_test.cpp, ridge_roll_test.cpp): no code of the planner's
// search.

#include <algorithm>
#include <cmath>

#include "freeturn/path/section_envelope.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::test {

// The largest height of the section g(ρ) at θ above the lower arc of the nose at
// (x, z), by brute force: n values of ρ across the nose, then ternary search.
inline double brute_overlap(const Surface& s, double x, double z, double R, double theta = 0,
                            int n = 20000) {
  const double ct = std::cos(theta), st = std::sin(theta);
  const auto h = [&](double rho) {
    const double d = rho - x;
    return s.sag(rho * ct, rho * st) - (z - std::sqrt(std::max(0.0, R * R - d * d)));
  };
  double best = -1e300, at = x;
  for (int i = 0; i <= n; ++i) {
    const double rho = x - 0.999 * R + 1.998 * R * i / n;
    if (h(rho) > best) best = h(rho), at = rho;
  }
  double lo = at - 1.998 * R / n, hi = at + 1.998 * R / n;
  for (int it = 0; it < 80; ++it) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (h(m1) > h(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::max(best, h(0.5 * (lo + hi)));
}

// The planner's placement for the contact at ρ on the section θ = 0.
inline NoseTouch touch_at(const Surface& s, double rho, double R) {
  double z, zx, zy;
  s.sag_gradient(rho, 0, z, zx, zy);
  return nose_touch(s, 0.0, R, rho, z, zx);
}

}  // namespace freeturn::test
