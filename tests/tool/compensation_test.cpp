#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/polynomial_height.hpp"
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
    // Centre height h: the edge is an arc in the rake plane, machine y = h. Turned back by
    // C into the machine's frame, the contact lies in that plane, R from the nose centre
    // (X, h, Z), and the arc's tangent there is perpendicular to the design's normal.
    c.tool.waviness.clear();
    const double slope_t = 0.3;  // a tangential slope as well, so that the plane matters
    p.normal = Eigen::Vector3d(-slope * std::cos(0.3) + slope_t * std::sin(0.3),
                               -slope * std::sin(0.3) - slope_t * std::cos(0.3), 1)
                   .normalized();
    for (const double h : {0.01, -0.05}) {
      c.tool.centre_height = h;
      const CutterLocation high = compensate(p, c);
      const double cc = std::cos(high.c), sc = std::sin(high.c);
      const Eigen::Vector3d q(p.point.x() * cc + p.point.y() * sc,
                              -p.point.x() * sc + p.point.y() * cc, p.point.z());
      const Eigen::Vector3d m(p.normal.x() * cc + p.normal.y() * sc,
                              -p.normal.x() * sc + p.normal.y() * cc, p.normal.z());
      CHECK(q.y() == doctest::Approx(h).epsilon(1e-14));
      const double dx = high.x - q.x(), dz = high.z - q.z();
      CHECK(std::hypot(dx, dz) == doctest::Approx(0.5).epsilon(1e-14));
      CHECK(std::abs(m.x() * dz - m.z() * dx) < 1e-14);
      // The contact on the near side of the nose: the centre above it.
      CHECK(dz > 0);
      // Back from the axes: the nose centre (X, h) turned by C, its distance from the
      // spindle and its angle.
      const double t_x = high.x * cc - h * sc, t_y = high.x * sc + h * cc;
      CHECK(nose_centre_from_axes(high.x, high.z, 0, c).x() ==
            doctest::Approx(std::hypot(t_x, t_y)).epsilon(1e-14));
      CHECK(work_angle_from_axes(high.c, high.x, 0, c) ==
            doctest::Approx(std::atan2(t_y, t_x)).epsilon(1e-14));
      // The checks keep the radial plane's nose, touching the same contact.
      CHECK((high.nose_centre - p.point).norm() == doctest::Approx(0.5).epsilon(1e-14));
    }
    // Under |h| from the axis the edge cannot reach the contact: no axes.
    c.tool.centre_height = 2.5;
    CHECK(std::isnan(compensate(p, c).x));
    c.tool.centre_height = 0;
    CHECK(work_angle_from_axes(0.7, 1.0, 0, c) == 0.7);
  }

  TEST_CASE(
      "centre height: the edge's arc, swept in the rake plane from the axes alone, "
      "touches the design at each block and stays above it") {
    // A paraboloid decentred by 1 mm (z = c((x − 1)² + y²)/2, c = 0.2): slopes to 0.4 mm/mm
    // across the radial sections as well as along them. The arc lies in machine y = h, its
    // centre at (X, h, Z) with the part turned by C: no compensation formula is used here.
    const double c = 0.2, R = 0.2;
    const PolynomialHeight design(1.0, 2, {c / 2, 0, c / 2, -c, 0, 0, c / 2, 0, 0});
    const auto z_of = [&](double x, double y) { return c * ((x - 1) * (x - 1) + y * y) / 2; };
    for (const double h : {0.01, -0.004}) {
      CAPTURE(h);
      CompensationOptions o;
      o.tool.nose_radius = R;
      o.tool.included_angle = 100 * std::numbers::pi / 180;
      o.tool.centre_height = h;
      ToolCheckOptions checks;
      checks.policy.fill(CheckPolicy::kOff);
      const auto cls = compensated_spiral(design, 1.0, o, checks);
      int swept = 0;
      double lowest = 1, highest = -1;
      for (const CutterLocation& cl : cls) {
        if (!std::isfinite(cl.x) || cl.contact.r < 0.1) continue;
        double gap = 1;
        for (int k = -5000; k <= 5000; ++k) {
          const double phi = 0.5 * o.tool.included_angle * k / 5000;
          const double x_m = cl.x - R * std::sin(phi), z = cl.z - R * std::cos(phi);
          const double x = x_m * std::cos(cl.c) - h * std::sin(cl.c);
          const double y = x_m * std::sin(cl.c) + h * std::cos(cl.c);
          gap = std::min(gap, z - z_of(x, y));
        }
        lowest = std::min(lowest, gap), highest = std::max(highest, gap);
        ++swept;
      }
      CHECK(swept > 300);
      // The arc's samples lie 1e-4 rad apart: R·(0.5e-4)²/2 = 0.25 pm above its lowest point.
      CHECK(lowest > -1e-12);
      CHECK(highest < 1e-9);
    }
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
