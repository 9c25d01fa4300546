#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/tool/tool_compensator.hpp"

using namespace freeturn;

namespace {

MachineDescription xzc() {
  MachineDescription m;
  m.name = "test-xzc";
  m.axes = {{Axis::kX}, {Axis::kZ}, {Axis::kC}};
  return m;
}

// A spiral with equal angles through compensation (R = 0: the contact is the programmed
// point) into the mapper.
DynamicsReport run(const Surface& s, const MachineDescription& m, const MotionOptions& motion,
                   std::vector<AxisRecord>* records = nullptr, int per_revolution = 100,
                   double pitch = 0.1, double outer = 4) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = pitch;
  o.points.rule = CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = per_revolution;
  CompensationOptions c;
  c.tool.nose_radius = 0;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  AxisCollector axes;
  AxisMapper mapper(m, motion, axes);
  ToolCompensator compensator(s, c, checks, mapper);
  plan_spiral(s, BaseSurface::plane(outer), o, compensator);
  if (records) *records = axes.records;
  return mapper.report();
}

// C turning 3.6° a block at r = 1 mm, 100 blocks, the last a third of one (1.2°): at 20 rpm
// h = 0.03 s a block, 120°/s.
std::vector<CutterLocation> c_turn_with_a_short_last_block() {
  const double step = 3.6 * std::numbers::pi / 180;
  std::vector<CutterLocation> cls(101);
  for (std::size_t k = 0; k < cls.size(); ++k) {
    CutterLocation& cl = cls[k];
    const double turned = k + 1 < cls.size() ? static_cast<double>(k) : k - 1 + 1.0 / 3;
    cl.contact.theta = cl.c = turned * step;
    cl.contact.r = cl.x = 1;
  }
  return cls;
}

}  // namespace

TEST_SUITE("machine") {
  TEST_CASE("axis values: signs, offsets, C wrapped or accumulating, block times from the rpm") {
    const EvenAsphere flat(0, 0);
    MachineDescription m = xzc();
    m.axes[0].sign = -1;
    m.axes[1].offset = 2.5;
    MotionOptions motion;
    motion.spindle_rpm = 30;  // 2 s per revolution
    std::vector<AxisRecord> r;
    const DynamicsReport report = run(flat, m, motion, &r);
    REQUIRE(r.size() == 4001);  // 40 revolutions × 100 + 1
    for (std::size_t k = 0; k < r.size(); ++k) {
      const double deg = 3.6 * static_cast<double>(k);
      CHECK(r[k].x == doctest::Approx(-(4 - 0.1 * static_cast<double>(k) / 100)).epsilon(1e-12).scale(1));
      CHECK(r[k].z == doctest::Approx(2.5).epsilon(1e-15));
      // Wrapped into [0, 360): the same angle modulo 360 (just below 360 counts).
      CHECK(std::abs(std::remainder(r[k].c - deg, 360.0)) < 1e-9);
      CHECK(r[k].c >= 0);
      CHECK(r[k].c < 360);
      if (k > 0) CHECK(r[k].time == doctest::Approx(0.02).epsilon(1e-10));
    }
    CHECK(report.cycle_time == doctest::Approx(80.0).epsilon(1e-12));
    m.c_wrapped = false;
    run(flat, m, motion, &r);
    CHECK(r.back().c == doctest::Approx(360.0 * 40).epsilon(1e-12));
  }

  TEST_CASE("dynamics: the highest rpm is set by X velocity (p·rpm/60) or Z acceleration") {
    MachineDescription m = xzc();
    m.axes[0].max_velocity = 0.01;  // mm/s; X moves pitch per revolution
    MotionOptions motion;
    motion.spindle_rpm = 1;
    motion.enforce_dynamics = false;
    const DynamicsReport a = run(EvenAsphere(0, 0), m, motion);
    // Within the margin m that leaves room for the rounding of written numbers.
    const double m_share = motion.margin;
    CHECK(a.max_rpm == doctest::Approx(m_share * 60 * 0.01 / 0.1).epsilon(1e-9));
    CHECK(a.limiting.find("X velocity") == 0);
    // A tilted flat z = 0.05x: Z = 0.05 r cos θ, acceleration ≈ 0.05 r ω² at the edge.
    MachineDescription tilt = xzc();
    tilt.axes[1].max_acceleration = 2.0;  // mm/s²
    // The motion judged is the words' (as_written): Z's second difference a block, 4.9e-5
    // mm at 400 blocks a turn, would carry 2 % of rounding at 6 decimals. At 10 the closed
    // form holds.
    for (AxisSpec& a : tilt.axes) a.decimals = 10;
    const DynamicsReport b = run(Alvarez(0, 0.05), tilt, motion, nullptr, 400);
    const double omega = std::sqrt(2.0 / (0.05 * 4));
    CHECK(b.max_rpm ==
          doctest::Approx(std::sqrt(m_share) * omega * 60 / (2 * std::numbers::pi)).epsilon(2e-3));
    CHECK(b.limiting.find("Z acceleration") == 0);
    // Enforced, a faster spindle is refused with the rpm this block allows.
    motion.spindle_rpm = 200;
    motion.enforce_dynamics = true;
    CHECK_THROWS_WITH_AS(run(Alvarez(0, 0.05), tilt, motion, nullptr, 400),
                         doctest::Contains("Z acceleration exceeds the machine's limit at 200 rpm"),
                         InputError);
  }

  TEST_CASE("PVT dynamics are the controller's cubics: twice the acceleration at a kink") {
    // X steps s1 per block, then s2 from block 100 on, then s3 from block 200 on; C 3.6° a
    // block at 20 rpm (h = 0.03 s). The controller's velocities are central differences,
    // so at the kink's block the velocity is (s1 + s2)/2h, and the cubics either side
    // accelerate by 2(s2 − s1)/h² at the kink (pvt_rule.hpp: a(0) = (6Δ − 4va − 2vb)/h),
    // twice what linear motion reads back, (s2 − s1)/h². The block after the kink
    // overshoots: its velocity a u² + b u + va peaks at u = 2/3 at s2 + (s2 − s1)/6, per h.
    // The second kink (s2 − s3 = 1.5e-3) and linear motion's stop after the last block
    // (s3/h²) are smaller.
    const double s1 = 1e-3, s2 = 3e-3, s3 = 1.5e-3, h = 0.03;
    std::vector<CutterLocation> cls(301);
    double x = 4;
    for (int k = 0; k <= 300; ++k) {
      CutterLocation& cl = cls[static_cast<std::size_t>(k)];
      cl.contact.theta = cl.c = k * 3.6 * std::numbers::pi / 180;
      cl.contact.r = cl.x = x;
      x -= k < 100 ? s1 : k < 200 ? s2 : s3;
    }
    MotionOptions motion;
    motion.spindle_rpm = 20;
    motion.enforce_dynamics = false;
    const auto peaks = [&](Interpolation interpolation) {
      MachineDescription m = xzc();
      m.interpolation = interpolation;
      m.axes[0].max_acceleration = 4;  // mm/s²: X sets the highest rpm
      AxisCollector axes;
      AxisMapper mapper(m, motion, axes);
      for (std::size_t k = 0; k < cls.size(); k += 64)
        mapper.write(std::span<const CutterLocation>(cls.data() + k,
                                                     std::min<std::size_t>(64, cls.size() - k)));
      mapper.finish();
      REQUIRE(axes.records.size() == cls.size());
      CHECK(axes.records.back().time == doctest::Approx(h).epsilon(1e-12));
      return mapper.report();
    };
    const DynamicsReport linear = peaks(Interpolation::kLinear);
    const DynamicsReport cubic = peaks(Interpolation::kCubic);
    // The kink, not the start from rest (s1/h² = 1.1 mm/s²) nor the stop (1.7), sets X's
    // figure.
    CHECK(linear.peak_acceleration[0] == doctest::Approx((s2 - s1) / (h * h)).epsilon(1e-9));
    CHECK(cubic.peak_acceleration[0] == doctest::Approx(2 * (s2 - s1) / (h * h)).epsilon(1e-9));
    CHECK(linear.peak_velocity[0] == doctest::Approx(s2 / h).epsilon(1e-9));
    CHECK(cubic.peak_velocity[0] == doctest::Approx((s2 + (s2 - s1) / 6) / h).epsilon(1e-9));
    // Acceleration ∝ rpm²: the highest rpm is 20·√(m·4 / a).
    CHECK(cubic.max_rpm ==
          doctest::Approx(20 * std::sqrt(motion.margin * 4 / (2 * (s2 - s1) / (h * h))))
              .epsilon(1e-9));
    CHECK(cubic.limiting.find("X acceleration at θ = 6.2831") == 0);  // at the kink's block
    CHECK(cubic.max_rpm == doctest::Approx(linear.max_rpm / std::sqrt(2.0)).epsilon(1e-9));
    // Enforced at 20 rpm (a 4.44 mm/s² kink against 0.98 × 4), the cubic's kink is
    // refused where linear motion's (2.22 mm/s²) passes.
    motion.enforce_dynamics = true;
    CHECK_NOTHROW(peaks(Interpolation::kLinear));
    CHECK_THROWS_WITH_AS(peaks(Interpolation::kCubic),
                         doctest::Contains("X acceleration exceeds the machine's limit at 20 rpm"),
                         InputError);
  }

  TEST_CASE("linear motion stops after the last block: a short last block sets the rpm") {
    // C turns 3.6° a block at 20 rpm (h = 0.03 s, 120°/s), the last block a third of one
    // (h/3). The start from rest asks 120/h = 4000°/s², the blocks between none, and the
    // stop 120/(h/3) = 12 000°/s²: against 6 000 allowed, the highest rpm is
    // 20·√(m·6000/12000), set by the stop at the last block's place.
    const double h = 0.03;
    const std::vector<CutterLocation> cls = c_turn_with_a_short_last_block();
    MachineDescription m = xzc();
    m.axes[2].max_acceleration = 6000;
    MotionOptions motion;
    motion.spindle_rpm = 20;
    motion.enforce_dynamics = false;
    AxisCollector axes;
    AxisMapper mapper(m, motion, axes);
    mapper.write(cls);
    // Before the end is known, the start from rest is the largest.
    CHECK(mapper.report().peak_acceleration[2] == doctest::Approx(120 / h).epsilon(1e-9));
    mapper.finish();
    CHECK(axes.records.back().time == doctest::Approx(h / 3).epsilon(1e-9));
    CHECK(mapper.report().peak_acceleration[2] == doctest::Approx(120 / (h / 3)).epsilon(1e-9));
    CHECK(mapper.report().max_rpm ==
          doctest::Approx(20 * std::sqrt(motion.margin * 0.5)).epsilon(1e-9));
    CHECK(mapper.report().limiting.find(
              "C acceleration (the stop after the last block) at θ = 6.2") == 0);
    // Enforced, the stop refuses 20 rpm.
    motion.enforce_dynamics = true;
    AxisMapper enforced(m, motion, axes);
    enforced.write(cls);
    CHECK_THROWS_WITH_AS(
        enforced.finish(),
        doctest::Contains("C acceleration (the stop after the last block) exceeds the "
                          "machine's limit at 20 rpm"),
        InputError);
  }

  TEST_CASE(
      "PVT stops after the last block too, and a profile is refused at the feed every block "
      "holds") {
    // The linear case's C (3.6° a block at 20 rpm, h = 0.03 s, the last block a third of
    // one) under PVT: the central differences give 120°/s at every block, the sliver's
    // included ((3.6 + 1.2)/(h + h/3)), so the cubics do not accelerate; the start reaches
    // 120°/s over h (4 000°/s²) and the stop leaves it over h/3 (12 000°/s²), as linear
    // motion does.
    const double h = 0.03;
    const std::vector<CutterLocation> cls = c_turn_with_a_short_last_block();
    MachineDescription m = xzc();
    m.interpolation = Interpolation::kCubic;
    m.axes[2].max_acceleration = 6000;
    MotionOptions motion;
    motion.spindle_rpm = 20;
    motion.enforce_dynamics = false;
    AxisCollector axes;
    AxisMapper mapper(m, motion, axes);
    mapper.write(cls);
    mapper.finish();
    CHECK(mapper.report().peak_acceleration[2] == doctest::Approx(120 / (h / 3)).epsilon(1e-9));
    CHECK(mapper.report().max_rpm ==
          doctest::Approx(20 * std::sqrt(motion.margin * 0.5)).epsilon(1e-9));
    CHECK(mapper.report().limiting.find(
              "C acceleration (the stop after the last block) at θ = 6.2") == 0);

    // A profile: X to the axis in 0.01 mm blocks, the last 0.0025 mm, Z still, at F mm/min
    // (v = F/60 throughout: the central differences are exact on it). The start from rest
    // asks v²/0.01, the stop v²/0.0025: against 0.98 × 500 mm/s², the start allows
    // F = 60·√(490 · 0.01) = 132.82 mm/min and the stop 60·√(490 · 0.0025) = 66.41.
    std::vector<CutterLocation> profile(101);
    for (int k = 0; k < 100; ++k)
      profile[static_cast<std::size_t>(k)].contact.r = profile[static_cast<std::size_t>(k)].x =
          0.0025 + 0.01 * (99 - k);  // the last, profile[100], on the axis
    MachineDescription lathe = xzc();
    lathe.axes.pop_back();  // X and Z: a profile turns no C
    lathe.interpolation = Interpolation::kCubic;
    lathe.axes[0].max_acceleration = 500;
    MotionOptions feed;
    feed.feed = 200;
    AxisMapper refused(lathe, feed, axes);
    refused.write(profile);
    // Refused at the end of the pass, with the feed the stop allows, not the start's.
    CHECK_THROWS_WITH_AS(
        refused.finish(),
        doctest::Contains("X acceleration on the controller's PVT cubics (the stop "
                          "after the last block) exceeds the machine's limit at "
                          "cutting.feed 200 mm/min: give a feed of at most 66.407"),
        InputError);
    CHECK(refused.report().max_feed == doctest::Approx(60 * std::sqrt(490 * 0.0025)).epsilon(1e-6));
    feed.feed = 66.4;
    AxisMapper held(lathe, feed, axes);
    held.write(profile);
    CHECK_NOTHROW(held.finish());
  }

  TEST_CASE("travel limits and a B the machine does not have are errors with their place") {
    MachineDescription m = xzc();
    m.axes[1].max = 0.2;  // Z travel
    MotionOptions motion;
    motion.spindle_rpm = 10;
    CHECK_THROWS_WITH_AS(run(EvenAsphere(1 / 10.0, 0), m, motion),
                         doctest::Contains("Z = 0.8") , InputError);
    CHECK_THROWS_WITH_AS(run(EvenAsphere(1 / 10.0, 0), m, motion),
                         doctest::Contains("is outside its travel [-inf, 0.2] on machine 'test-xzc'"),
                         InputError);
    // A mapper without rpm on a C machine is refused at once.
    AxisCollector sink;
    CHECK_THROWS_WITH_AS(AxisMapper(xzc(), MotionOptions{}, sink),
                         doctest::Contains("give the spindle speed"), InputError);
  }
}
