#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/section_curvature.hpp"
#include "freeturn/surface/transformed_surface.hpp"

using namespace freeturn;

TEST_SUITE("surface") {
  TEST_CASE("a radial section's curvature: a decentred sphere's circles, in closed form") {
    // A bowl of radius ρ = 2 decentred by d = 0.5: the radial plane at θ passes d|sin θ|
    // from the sphere's centre and cuts it in a circle of radius √(ρ² − d² sin² θ).
    const double rho = 2, d = 0.5;
    const TransformedSurface bowl(std::make_unique<EvenAsphere>(1 / rho, 0), d, 0,
                                  Eigen::Matrix3d::Identity());
    for (const double theta : {0.0, 0.4, 1.0, std::numbers::pi / 2, 2.5, 4.0})
      for (const double r : {0.0, 0.3, 0.9}) {
        const double s = std::sin(theta);
        CHECK(radial_section_curvature(bowl, RadialLine(theta), r) ==
              doctest::Approx(1 / std::sqrt(rho * rho - d * d * s * s)).epsilon(1e-9));
      }
    // A dome bends away from the tool: negative.
    CHECK(radial_section_curvature(EvenAsphere(-1 / rho, 0), RadialLine(0.3), 0.5) ==
          doctest::Approx(-1 / rho).epsilon(1e-12));
    // The largest over the annulus: the θ = 90° circles', within the grid's margin (its
    // largest change between neighbours, here along the circles).
    const double largest = largest_section_curvature(bowl, 0, 0.9);
    const double exact = 1 / std::sqrt(rho * rho - d * d);
    CHECK(largest >= exact);
    CHECK(largest <= exact * (1 + 1e-3));
    // A centred sphere's sections are all great circles: no change, the value itself.
    CHECK(largest_section_curvature(EvenAsphere(1 / rho, 0), 0.1, 0.9) ==
          doctest::Approx(1 / rho).epsilon(1e-12));
  }
}
