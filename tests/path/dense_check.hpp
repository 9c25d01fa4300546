#pragma once
// An independent check of chord errors: the machine's linear motion in (X, C, Z) between
// consecutive contact points, sampled densely, against the design surface.

#include <algorithm>
#include <cmath>
#include <vector>

#include "freeturn/path/contact_point.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn::test {

// The largest distance from the surface over every segment, 200 samples each.
inline double densest_chord_error(const Surface& s, const std::vector<ContactPoint>& path,
                                  int samples = 200) {
  double worst = 0;
  for (std::size_t k = 1; k < path.size(); ++k) {
    const ContactPoint &a = path[k - 1], &b = path[k];
    for (int j = 1; j < samples; ++j) {
      const double t = static_cast<double>(j) / samples;
      const double r = a.r + t * (b.r - a.r), c = a.theta + t * (b.theta - a.theta),
                   z = a.point.z() + t * (b.point.z() - a.point.z());
      double f, fx, fy;
      s.sag_gradient(r * std::cos(c), r * std::sin(c), f, fx, fy);
      worst = std::max(worst, std::abs(z - f) / std::sqrt(1 + fx * fx + fy * fy));
    }
  }
  return worst;
}

}  // namespace freeturn::test
