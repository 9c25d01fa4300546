#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.hpp"
#include "freeturn/nurbs/curve_locator.hpp"

using namespace freeturn::test;
using freeturn::Status;
using freeturn::nurbs::CurveLocator;

TEST_SUITE("nurbs") {
  TEST_CASE("curve inversion on a full circle: radial projection, across the seam") {
    const double r = 3.0;
    const CurveLocator locator(full_circle(r));
    CHECK(locator.closed());
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> angle(-3.14, 3.14), radius(0.5, 6);
    for (int k = 0; k < 1000; ++k) {
      const double a = angle(rng), rr = radius(rng);
      const Vector3d p(rr * std::cos(a), rr * std::sin(a), 0.2);
      const auto cold = locator.closest_point(p);
      const auto warm = locator.closest_point(p, 0.999);  // starts across the seam for a < 0
      const Vector3d expected = Vector3d(std::cos(a), std::sin(a), 0) * r;
      for (const auto& res : {cold, warm}) {
        CHECK(res.status == Status::kOk);
        CHECK((res.point - expected).norm() <= 1e-10);
        CHECK(res.distance == doctest::Approx(std::hypot(rr - r, 0.2)).epsilon(1e-12));
      }
    }
  }

  TEST_CASE("curve inversion stops at an end when the curve leads away") {
    const CurveLocator locator(quarter_circle(2.0));
    const auto beyond_start = locator.closest_point({3, -1, 0});
    CHECK(beyond_start.u == 0.0);
    CHECK((beyond_start.point - Vector3d(2, 0, 0)).norm() <= 1e-15);
    const auto beyond_end = locator.closest_point({-1, 3, 0}, 0.5);
    CHECK(beyond_end.u == 1.0);
    CHECK(beyond_end.distance == doctest::Approx(std::sqrt(2.0)).epsilon(1e-14));
  }
}
