#include <doctest/doctest.h>

#include <cmath>

#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "freeturn/verify/cut_simulation.hpp"

using namespace freeturn;

namespace {

// A flat face cut by a planar spiral of pitch f (equal angles aligned with the grid's
// columns), compensated for nose radius `planned`, simulated with nose radius `actual`.
SimulationResult cut_flat(double f, double planned, double actual) {
  const EvenAsphere flat(0, 0);
  SpiralOptions o;
  o.outer_radius = 2.0;
  o.pitch = f;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 8;
  CompensationOptions c;
  c.tool.nose_radius = planned;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  SimulationOptions s;
  s.inner_radius = 0.5;  // away from the first and last turns
  s.outer_radius = 1.5;
  s.radial_step = f / 2000;
  s.columns = 8;
  s.band = 2 * f;
  CutSimulator simulator(flat, actual, s);
  ToolCompensator compensator(flat, c, checks, simulator);
  plan_spiral(flat, BaseSurface::plane(2.0), o, compensator);
  return simulator.result();
}

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE("flat face: the scallop between passes f apart is R − √(R² − f²/4) to 1e-3") {
    const double f = 0.05, R = 0.5;
    const SimulationResult r = cut_flat(f, R, R);
    CHECK(r.uncut == 0);
    const double scallop = R - std::sqrt(R * R - f * f / 4);
    CHECK(r.max == doctest::Approx(scallop).epsilon(1e-3));
    CHECK(r.pv == doctest::Approx(scallop).epsilon(1e-3));
    CHECK(r.min >= -1e-12);  // nowhere below the design
  }

  TEST_CASE("a nose 1 µm larger than planned cuts 1 µm too deep") {
    const double f = 0.05, R = 0.5;
    const SimulationResult r = cut_flat(f, R, R + 0.001);
    CHECK(r.min == doctest::Approx(-0.001).epsilon(1e-3));
    // The scallop of the larger nose rides on the 1 µm offset.
    const double scallop = (R + 0.001) - std::sqrt((R + 0.001) * (R + 0.001) - f * f / 4);
    CHECK(r.max == doctest::Approx(scallop - 0.001).epsilon(1e-2));
  }
}

#include "freeturn/surface/transformed_surface.hpp"

TEST_SUITE("verify") {
  TEST_CASE("an off-axis sphere cut with chord tolerance: the residual is bounded by the prediction and close to it") {
    // A sphere of R 30 mm decentred 8 mm: its sag varies around the spindle, so the chord
    // error between blocks matters as much as the scallop.
    const TransformedSurface sphere(std::make_unique<EvenAsphere>(1 / 30.0, 0), 8, 0,
                                    Eigen::Matrix3d::Identity());
    const double eps = 5e-4, f = 0.01, R = 0.5;
    SpiralOptions o;
    o.outer_radius = 1.2;
    o.pitch = f;
    o.nose_radius = R;
    o.points.tolerance = eps;
    o.points.max_angle_step = 0.05;
    CompensationOptions c;
    c.tool.nose_radius = R;
    ToolCheckOptions checks;
    checks.policy.fill(CheckPolicy::kOff);
    SimulationOptions s;
    s.inner_radius = 0.5;
    s.outer_radius = 1.0;
    s.radial_step = f / 100;
    s.columns = 1024;
    s.band = 3 * f;
    CutSimulator simulator(sphere, R, s);
    struct Tee final : CutterSink {
      CutSimulator* sim = nullptr;
      double chord = 0, scallop = 0;
      void write(std::span<const CutterLocation> chunk) override {
        for (const CutterLocation& cl : chunk) {
          const double r = cl.contact.r;
          if (r > 0.5 && r < 1.0) {
            chord = std::max(chord, cl.contact.chord_error);
            scallop = std::max(scallop, cl.contact.scallop);
          }
        }
        sim->write(chunk);
      }
    } tee;
    tee.sim = &simulator;
    ToolCompensator compensator(sphere, c, checks, tee);
    plan_spiral(sphere, BaseSurface::plane(1.2), o, compensator);
    const SimulationResult r = simulator.result();
    const double predicted = tee.chord + tee.scallop;
    MESSAGE("simulated PV " << r.pv * 1e6 << " nm, max " << r.max * 1e6 << " nm; predicted chord "
                            << tee.chord * 1e6 << " + scallop " << tee.scallop * 1e6 << " nm");
    CHECK(r.uncut == 0);
    // The interpolated tool motion leaves the design on both sides: material above it up to
    // chord + scallop, a cut below it up to the chord error. The planner's figures bound
    // each side, and are not loose.
    CHECK(r.max <= 1.02 * predicted);
    CHECK(-r.min <= 1.02 * tee.chord);
    CHECK(-r.min >= 0.8 * tee.chord);
    CHECK(r.pv <= 1.02 * (2 * tee.chord + tee.scallop));
    CHECK(r.pv >= 0.8 * predicted);
  }
}
