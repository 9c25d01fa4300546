#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/zernike.hpp"
#include "path/dense_check.hpp"

using namespace freeturn;

namespace {

// Sinusoidal ring of paper 001: z = A sin(ωr) + d, here A = 0.05 mm, period 2 mm, on
// r ≤ 10 mm.
constexpr double kA = 0.05, kOmega = std::numbers::pi, kRadius = 10.0;

// ∫ √(κ / 8ε) ds along the profile, with κ = |z''|/(1 + z'²)^{3/2} and ds = √(1 + z'²) dr:
// the fewest points that keep every chord under ε (Simpson's rule, 20000 intervals).
double lower_bound(double eps) {
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = kRadius * i / n;
    const double d1 = kA * kOmega * std::cos(kOmega * r), d2 = -kA * kOmega * kOmega * std::sin(kOmega * r);
    const double kappa = std::abs(d2) / std::pow(1 + d1 * d1, 1.5);
    const double f = std::sqrt(kappa / (8 * eps)) * std::sqrt(1 + d1 * d1);
    sum += f * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
  }
  return sum * kRadius / n / 3;
}

std::vector<ContactPoint> profile(const Surface& s, CutterPointOptions points) {
  ProfileOptions o;
  o.outer_radius = kRadius;
  o.points = points;
  ContactCollector out;
  plan_profile(s, o, out);
  return out.points;
}

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("profile: sinusoidal ring, chord-controlled points hold ε with ≤ 1.1× the lower bound") {
    const SinusoidalRing ring(kA, kOmega, 0.0);
    for (double eps : {1e-3, 1e-4}) {
      CAPTURE(eps);
      CutterPointOptions o;
      o.rule = CutterPointRule::kChordError;
      o.tolerance = eps;
      o.max_radial_step = 1.0;
      const auto path = profile(ring, o);
      const double worst = test::densest_chord_error(ring, path);
      CHECK(worst <= eps);
      const double bound = lower_bound(eps);
      CHECK(static_cast<double>(path.size()) <= 1.1 * bound);
      // The planner's own per-segment estimate agrees with the dense check.
      double estimated = 0;
      for (const auto& p : path) estimated = std::max(estimated, p.chord_error);
      CHECK(estimated == doctest::Approx(worst).epsilon(0.02).scale(0));
      // Equal spacing with the same worst error needs the step of the most curved place.
      // Find it by bisection on the arc length, checked densely.
      double lo = 1e-4, hi = 1.0;
      for (int it = 0; it < 30; ++it) {
        const double mid = std::sqrt(lo * hi);
        CutterPointOptions e;
        e.rule = CutterPointRule::kEqualArcLength;
        e.arc_length = mid;
        e.max_radial_step = 1.0;
        (test::densest_chord_error(ring, profile(ring, e)) <= eps ? lo : hi) = mid;
      }
      CutterPointOptions e;
      e.rule = CutterPointRule::kEqualArcLength;
      e.arc_length = lo;
      e.max_radial_step = 1.0;
      const auto equal = profile(ring, e);
      MESSAGE("ε = " << eps * 1e3 << " µm: " << path.size() << " points (lower bound " << bound
                     << "), equal spacing " << equal.size());
      CHECK(static_cast<double>(path.size()) < 0.8 * static_cast<double>(equal.size()));
    }
  }

  TEST_CASE("profile: runs exactly from the edge to the centre, in order") {
    const EvenAsphere asphere(1 / 30.0, -1.5, {2e-5});
    CutterPointOptions o;
    o.tolerance = 1e-4;
    const auto path = profile(asphere, o);
    REQUIRE(path.size() > 2);
    CHECK(path.front().r == kRadius);
    CHECK(path.back().r == 0.0);
    for (std::size_t k = 1; k < path.size(); ++k) {
      CHECK(path[k].r < path[k - 1].r);
      CHECK(path[k - 1].r - path[k].r <= o.max_radial_step * (1 + 1e-12));
      CHECK(path[k].point.z() == asphere.sag(path[k].r, 0));
    }
  }

  TEST_CASE("profile: a surface that is not rotationally symmetric is refused") {
    const Zernike z(0.0, 0.0, {}, 10.0, {0, 0, 0, 0, 0, 1e-4});  // Z6: astigmatism
    CutterPointOptions o;
    CHECK_THROWS_WITH_AS(profile(z, o),
                         doctest::Contains("not rotationally symmetric"), InputError);
  }
}
