#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/tool_compensator.hpp"

using namespace freeturn;

namespace {

std::vector<CutterLocation> compensated_spiral(const Surface& s, double outer,
                                               const CompensationOptions& c,
                                               ToolCheckOptions checks = {}) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = 0.1;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 37;
  checks.outer_radius = outer;
  CutterCollector out;
  ToolCompensator compensator(s, c, checks, out);
  plan_spiral(s, BaseSurface::plane(outer), o, compensator);
  return out.locations;
}

}  // namespace

TEST_SUITE("tool") {
  TEST_CASE("sphere: nose centres lie on the offset sphere, R from the contact, in its radial plane") {
    for (double radius : {20.0, -15.0}) {
      CAPTURE(radius);
      const EvenAsphere sphere(1 / radius, 0);
      CompensationOptions c;
      c.tool.nose_radius = 0.5;
      const auto cls = compensated_spiral(sphere, 5.0, c);
      REQUIRE(cls.size() > 100);
      const Eigen::Vector3d centre(0, 0, radius);
      for (const CutterLocation& cl : cls) {
        // The offset of a sphere toward its centre (concave, R > 0) or away (convex).
        CHECK((cl.nose_centre - centre).norm() ==
              doctest::Approx(std::abs(radius) - std::copysign(0.5, radius)).epsilon(1e-12));
        CHECK((cl.nose_centre - cl.contact.point).norm() == doctest::Approx(0.5).epsilon(1e-12));
        const Eigen::Vector3d e_theta(-std::sin(cl.contact.theta), std::cos(cl.contact.theta), 0);
        CHECK(std::abs(cl.nose_centre.dot(e_theta)) < 1e-12);
        CHECK(cl.x == doctest::Approx(cl.nose_centre.head<2>().dot(
                                          Eigen::Vector2d(std::cos(cl.contact.theta),
                                                          std::sin(cl.contact.theta))))
                          .epsilon(1e-15)
                          .scale(1));
      }
    }
  }

  TEST_CASE("asphere profile: the nose centre is the closed-form offset curve to 1e-9 mm") {
    const double c = 1 / 25.0, k = -2.0, a4 = 3e-5, R = 0.3;
    const EvenAsphere asphere(c, k, {a4});
    ProfileOptions o;
    o.outer_radius = 8;
    o.points.tolerance = 1e-5;
    CompensationOptions comp;
    comp.tool.nose_radius = R;
    CutterCollector out;
    ToolCheckOptions checks;
    checks.outer_radius = 8;
    ToolCompensator compensator(asphere, comp, checks, out);
    plan_profile(asphere, o, compensator);
    for (const CutterLocation& cl : out.locations) {
      const double r = cl.contact.r;
      // z'(r) in closed form: c r / √(1 − (1+k)c²r²) + 4 A4 r³.
      const double d = c * r / std::sqrt(1 - (1 + k) * c * c * r * r) + 4 * a4 * r * r * r;
      const double norm = std::sqrt(1 + d * d);
      CHECK(cl.x == doctest::Approx(r - R * d / norm).epsilon(1e-9).scale(1));
      CHECK(cl.z == doctest::Approx(asphere.sag(r, 0) + R / norm).epsilon(1e-9).scale(1));
      CHECK(cl.psi == doctest::Approx(std::atan(-d)).epsilon(1e-12).scale(1));
    }
  }

  TEST_CASE("program point at the tip and waviness move the programmed point as specified") {
    ContactPoint p;
    p.theta = 0.3;
    p.r = 2.0;
    const double slope = 0.2;
    p.point = {2 * std::cos(0.3), 2 * std::sin(0.3), 0.4};
    p.normal = Eigen::Vector3d(-slope * std::cos(0.3), -slope * std::sin(0.3), 1).normalized();
    CompensationOptions c;
    c.tool.nose_radius = 0.5;
    const CutterLocation centre = compensate(p, c);
    c.tool.program_point = ProgramPoint::kTip;
    const CutterLocation tip = compensate(p, c);
    CHECK(tip.x == doctest::Approx(centre.x).epsilon(1e-15));
    CHECK(tip.z == doctest::Approx(centre.z - 0.5).epsilon(1e-15));
    // Waviness +2 µm at this contact angle (ψ = −atan 0.2): the centre moves 2 µm out.
    c.tool.program_point = ProgramPoint::kNoseCentre;
    c.tool.waviness = {{-0.5, 0.002}, {0.5, 0.002}};
    const CutterLocation wavy = compensate(p, c);
    CHECK((wavy.nose_centre - p.point).norm() == doctest::Approx(0.502).epsilon(1e-14));
    // Centre height h: the edge at machine X touches radius √(X² + h²).
    c.tool.waviness.clear();
    c.tool.centre_height = 0.01;
    const CutterLocation high = compensate(p, c);
    CHECK(std::hypot(high.x, 0.01) == doctest::Approx(centre.x).epsilon(1e-15));
    CHECK(high.c == doctest::Approx(0.3 - std::atan2(0.01, high.x)).epsilon(1e-15));
    // Back from the axes: the nose centre sits where the edge's line through (X, h) turned
    // by C meets it, at the contact's angle θ = 0.3 and radius c_r.
    const double x_work = high.x * std::cos(high.c) - 0.01 * std::sin(high.c);
    const double y_work = high.x * std::sin(high.c) + 0.01 * std::cos(high.c);
    CHECK(work_angle_from_axes(high.c, high.x, c) ==
          doctest::Approx(std::atan2(y_work, x_work)).epsilon(1e-15));
    CHECK(work_angle_from_axes(high.c, high.x, c) == doctest::Approx(0.3).epsilon(1e-14));
    c.tool.centre_height = 0;
    CHECK(work_angle_from_axes(high.c, high.x, c) == high.c);
  }

  TEST_CASE("4-axis: B follows ψ; axis values → nose centre → contact round trip to 1e-9 mm") {
    const EvenAsphere asphere(1 / 12.0, -0.5);
    CompensationOptions c;
    c.tool.nose_radius = 0.4;
    c.b_mode = BMode::kFollow;
    c.pivot_distance = 35.0;
    ToolCheckOptions checks;
    checks.b_min = -1.0;
    checks.b_max = 1.0;
    const auto cls = compensated_spiral(asphere, 5.0, c, checks);
    for (const CutterLocation& cl : cls) {
      CHECK(cl.b == doctest::Approx(cl.psi).epsilon(1e-15).scale(1));
      const Eigen::Vector2d nose = nose_centre_from_axes(cl.x, cl.z, cl.b, c);
      // The contact is R back along the in-plane normal, which B now points along.
      const Eigen::Vector2d contact = nose - 0.4 * Eigen::Vector2d(std::sin(cl.b), std::cos(cl.b));
      const double ct = std::cos(cl.contact.theta), st = std::sin(cl.contact.theta);
      const Eigen::Vector3d back(contact.x() * ct, contact.x() * st, contact.y());
      CHECK((back - cl.contact.point).norm() < 1e-9);
    }
  }
}
