#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "freeturn/surface/surface.hpp"

using namespace freeturn;

TEST_SUITE("surface") {
  TEST_CASE("a radial line turned through a small angle is the line at that angle, to rounding") {
    // Against libm's sine and cosine of the angle itself, from bases all round the turn,
    // through angles up to the series' reach (1/16 rad) and past it (the pair is taken then).
    double worst = 0;
    for (int i = 0; i < 64; ++i) {
      const RadialLine base(-7.0 + 0.37 * i);
      for (const double delta :
           {0.0, 1e-12, -3e-7, 1e-3, -0.02, 0.0625, -0.0625, 0.07, -1.5, 4.0}) {
        const double angle = base.theta + delta;
        const RadialLine turned = base.turned_to(angle);
        CHECK(turned.theta == angle);
        worst = std::max({worst, std::abs(turned.cos - std::cos(angle)),
                          std::abs(turned.sin - std::sin(angle))});
      }
    }
    MESSAGE("largest difference from libm: " << worst);
    CHECK(worst <= 4e-16);
    // Beyond the series' reach the line is the pair's own.
    const RadialLine far = RadialLine(0.3).turned_to(0.3 + 0.07);
    CHECK(far.cos == std::cos(0.3 + 0.07));
    CHECK(far.sin == std::sin(0.3 + 0.07));
  }
}
