#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/tool/clearance.hpp"

using namespace freeturn;

namespace {

// A convex sphere (R = 20 mm) moved so that its vertex, its highest point, lies between
// the grid's nodes at r = 2.345 mm, θ = 0.123 rad.
constexpr double kCurvature = -1 / 20.0, kPeakR = 2.345, kPeakTheta = 0.123;

TransformedSurface moved_sphere() {
  return TransformedSurface(std::make_unique<EvenAsphere>(kCurvature, 0.0),
                            -kPeakR * std::cos(kPeakTheta), -kPeakR * std::sin(kPeakTheta),
                            Eigen::Matrix3d::Identity());
}

// The parent's sag at the decentre, c r²/(1 + √(1 − c² r²)): the world frame puts that
// point at z = 0, so the vertex stands at −f there.
double peak_height() {
  const double c = kCurvature, r2 = kPeakR * kPeakR;
  return -c * r2 / (1 + std::sqrt(1 - c * c * r2));
}

}  // namespace

TEST_SUITE("tool") {
  TEST_CASE("the highest sag between grid nodes is found to a nanometre") {
    const TransformedSurface s = moved_sphere();
    CHECK(std::abs(highest_sag(s, 0, 5) - peak_height()) < 1e-9);
    // An annulus that leaves the vertex out: the highest point is on its inner edge, on
    // the vertex's side, R·(1 − cos) lower than the vertex over the 0.655 mm between.
    const double d = 3 - kPeakR;
    const double expected = peak_height() - 20 * (1 - std::cos(std::asin(d / 20)));
    CHECK(std::abs(highest_sag(s, 3, 5) - expected) < 1e-9);
  }

  TEST_CASE("the programmed Z ceiling adds the nose, the stand-off and the programmed point") {
    const EvenAsphere convex(kCurvature, 0.0);  // its top is the vertex, z = 0
    CompensationOptions o;
    o.tool.nose_radius = 0.5;
    CHECK(program_z_ceiling(convex, 0, 4, o, 0.002) ==
          doctest::Approx(0.5 + 0.002 + kCeilingMargin).epsilon(1e-12));
    o.tool.waviness = {{-0.5, -0.0003}, {0.5, 0.0004}};  // the largest δ widens the nose
    CHECK(program_z_ceiling(convex, 0, 4, o, 0) ==
          doctest::Approx(0.5004 + kCeilingMargin).epsilon(1e-12));
    o.tool.waviness.clear();
    o.tool.program_point = ProgramPoint::kTip;  // the tip is R below the centre at B = 0
    CHECK(program_z_ceiling(convex, 0, 4, o, 0) == doctest::Approx(kCeilingMargin).epsilon(1e-12));
    o.pivot_distance = 50;  // a B pivot 50 mm above the nose centre
    CHECK(program_z_ceiling(convex, 0, 4, o, 0) ==
          doctest::Approx(50.5 + kCeilingMargin).epsilon(1e-12));
  }
}
