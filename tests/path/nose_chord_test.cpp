#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/path/profile.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "path/dense_check.hpp"

using namespace freeturn;

namespace {

std::vector<CutterLocation> compensated(const Surface& s, double R, const auto& plan,
                                        CompensationOptions c = {}) {
  c.tool.nose_radius = R;
  ToolCheckOptions checks;
  checks.policy.fill(CheckPolicy::kOff);
  CutterCollector out;
  ToolCompensator compensator(s, c, checks, out);
  plan(compensator);
  return out.locations;
}

std::vector<ContactPoint> contacts(const std::vector<CutterLocation>& cls) {
  std::vector<ContactPoint> p;
  for (const CutterLocation& cl : cls) p.push_back(cl.contact);
  return p;
}

// The sphere of radius 30 mm decentred 8 mm (slope on the axis): the nose centre's path
// curves around the turn differently from the contact's. A spiral over [inner, 1] mm at a
// 0.05 mm pitch with a nose of radius R, ε as given, steps up to 1 rad.
const TransformedSurface decentred_sphere(std::make_unique<EvenAsphere>(1 / 30.0, 0), 8, 0,
                                          Eigen::Matrix3d::Identity());
// A spiral over [inner, outer] mm at `pitch` with a nose of radius R, planned by chord ε,
// steps up to `max_angle` rad.
SpiralOptions nose_spiral(double outer, double inner, double pitch, double eps, double R,
                          double max_angle = 1.0, Interpolation mode = Interpolation::kLinear) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.inner_radius = inner;
  o.pitch = pitch;
  o.tool.nose_radius = R;
  o.points.tolerance = eps;
  o.points.max_angle_step = max_angle;
  o.points.interpolation = mode;
  return o;
}
SpiralOptions sphere_spiral(double inner, double eps, double R, Interpolation mode) {
  return nose_spiral(1.0, inner, 0.05, eps, R, 1.0, mode);
}

// The largest chord error the planner reported for its own segments.
double largest_planned_chord(const std::vector<CutterLocation>& cls) {
  double planned = 0;
  for (const CutterLocation& cl : cls) planned = std::max(planned, cl.contact.chord_error);
  return planned;
}

// Paper 001's sinusoidal ring, period 2 mm, in profile from 5 mm to 0.5 mm: away from the
// centre, where the profile meets its mirror image in a cone tip.
const SinusoidalRing ring(0.05, std::numbers::pi, 0.0);
ProfileOptions ring_profile(double eps, double R, Interpolation mode) {
  ProfileOptions o;
  o.outer_radius = 5.0;
  o.inner_radius = 0.5;
  o.tool.nose_radius = R;
  o.points.tolerance = eps;
  o.points.interpolation = mode;
  return o;
}

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("with a nose, ε holds on the nose-centre motion the machine interpolates (spiral)") {
    const TransformedSurface& sphere = decentred_sphere;
    const double eps = 5e-4, R = 0.5;
    const SpiralOptions o = sphere_spiral(0.5, eps, R, Interpolation::kLinear);
    const auto cls = compensated(sphere, R, [&](ContactSink& sink) {
      plan_spiral(sphere, BaseSurface::plane(1.0), o, sink);
    });
    const double nose = test::densest_nose_error(sphere, cls, R);
    const double contact = test::densest_chord_error(sphere, contacts(cls));
    MESSAGE("ε " << eps * 1e6 << " nm: nose motion " << nose * 1e6 << " nm, contact path "
                 << contact * 1e6 << " nm, " << cls.size() << " points");
    CHECK(nose <= 1.002 * eps);
    CHECK(nose >= 0.9 * eps);
    // The planner's own figure per segment agrees with the brute force.
    CHECK(largest_planned_chord(cls) == doctest::Approx(nose).epsilon(0.01).scale(0));
  }

  TEST_CASE("an asphere off its axis: a segment's peak from its fourths is the dense sampler's") {
    // A smooth segment's peak is settled from its samples at 1/4, 1/2 and 3/4 where they and
    // the blocks' zeros lie on one parabola (path_stepper.hpp, peak_of_one_parabola), and
    // from its eighths elsewhere. Off its axis this asphere's sections change curvature
    // along each chord (the A4 and A6 terms), so the chords' sags are not symmetric: the
    // planner's figure must still be the dense sampler's to 1 %, and ε must hold.
    const TransformedSurface asphere(
        std::make_unique<EvenAsphere>(1 / 20.0, -1.5, std::array<double, 9>{2e-4, -1e-5}), 3, 1,
        Eigen::Matrix3d::Identity());
    const double eps = 3e-4, R = 0.5;
    const SpiralOptions o = nose_spiral(1.5, 0.3, 0.05, eps, R);
    const auto cls = compensated(asphere, R, [&](ContactSink& sink) {
      plan_spiral(asphere, BaseSurface::plane(1.5), o, sink);
    });
    const double nose = test::densest_nose_error(asphere, cls, R);
    const double planned = largest_planned_chord(cls);
    MESSAGE("ε " << eps * 1e6 << " nm: nose motion " << nose * 1e6 << " nm, planned "
                 << planned * 1e6 << " nm, " << cls.size() << " points");
    CHECK(nose <= 1.002 * eps);
    CHECK(nose >= 0.9 * eps);
    CHECK(planned == doctest::Approx(nose).epsilon(0.01).scale(0));
  }

  TEST_CASE("a nose that just fits the troughs: the chords never dip below the design") {
    // A sinusoidal grid (20 µm, 0.8 mm wavelengths) bends toward the tool up to 1/0.81
    // mm⁻¹; under a 0.8 mm nose the overlap's search from the interpolated contact used to
    // stop a tenth of the way to its peak, and a 1 µm chord plan cut up to 61 nm into the
    // design between blocks (an NC-free check of the program, r 2.9 mm). Every chord of
    // this spiral must keep the nose above the design (the band's lower edge, 0) and
    // within ε of it.
    const SinusoidalGrid grid(0.02, 0.8, 0.8);
    const double eps = 1e-3, R = 0.8;
    const SpiralOptions o = nose_spiral(3.0, 2.6, 0.02, eps, R, 5 * std::numbers::pi / 180);
    const auto cls = compensated(
        grid, R, [&](ContactSink& sink) { plan_spiral(grid, BaseSurface::plane(3.0), o, sink); });
    const test::DenseNoseFigures f = test::dense_nose_figures(grid, cls, R, 24, 300);
    MESSAGE(cls.size() << " points: the nose " << f.lowest * 1e6 << " to " << f.highest * 1e6
                       << " nm above the design");
    CHECK(f.lowest >= -1e-9);
    CHECK(f.highest <= 1.002 * eps);
  }

  TEST_CASE("with a nose, ε holds on the nose-centre motion (profile)") {
    {
      const double eps = 1e-4, R = 0.2;
      const ProfileOptions o = ring_profile(eps, R, Interpolation::kLinear);
      const auto cls =
          compensated(ring, R, [&](ContactSink& sink) { plan_profile(ring, o, sink); });
      const double nose = test::densest_nose_error(ring, cls, R, 200);
      MESSAGE("profile ε " << eps * 1e6 << " nm: nose motion " << nose * 1e6 << " nm, "
                           << cls.size() << " points");
      CHECK(nose <= 1.002 * eps);
      CHECK(nose >= 0.9 * eps);
    }
  }

  TEST_CASE("PVT: ε holds on the controller's cubics, with velocities from neighbouring blocks") {
    // The planner's figure must be the one a dense sampler finds on the cubics a controller
    // given positions only would run (dense_check.hpp writes that rule out on its own).
    const auto judge = [](const Surface& s, const std::vector<CutterLocation>& cls, double R,
                          double eps, const std::string& what) {
      const test::DenseNoseFigures f = test::dense_nose_figures(s, cls, R, 100, 400, nullptr, true);
      double planned = 0;
      for (const CutterLocation& cl : cls) planned = std::max(planned, cl.contact.chord_error);
      MESSAGE(what << ": ε " << eps * 1e6 << " nm, PVT motion " << f.worst * 1e6 << " nm, planned "
                   << planned * 1e6 << " nm, deepest " << f.gouge * 1e6 << " nm below, "
                   << cls.size() << " points");
      CHECK(f.worst <= 1.002 * eps);
      CHECK(f.gouge <= 1e-9);
      CHECK(planned == doctest::Approx(f.worst).epsilon(0.02).scale(0));
      // Segment by segment the planner's figure is the band's (ContactPoint::chord_error):
      // the stand-off plus the motion's largest deviation from it either way, as the
      // sampler finds it (highest and lowest distance above the design, here along the
      // radial section's normal, as the planner measures). On a segment whose worst
      // deviation dips toward the design (a one-sided end velocity's cubic) that is more
      // than the motion's largest distance from the design: the ring's first segment reads
      // 67.7 nm where the nose stays 32.3 to 50.1 nm above it. Scaled to the surface's own
      // normal instead, the spiral's segments differ from the figure by −8.9 to +13.8 nm of
      // ε = 500 nm (the sphere's slope across the section), to 0.12 nm along the section's.
      double worst_identity = 0;
      for (std::size_t k = 1; k < cls.size(); ++k) {
        const test::DenseNoseFigures g =
            test::dense_nose_figures(s, cls, R, 100, 400, nullptr, true, k, true);
        const double stand_off = cls[k].contact.stand_off;
        const double band = stand_off + std::max(g.highest - stand_off, stand_off - g.lowest);
        worst_identity = std::max(worst_identity, std::abs(cls[k].contact.chord_error - band));
      }
      MESSAGE(what << ": the planner's figure against the band's from the sampler, worst "
                   << worst_identity * 1e6 << " nm apart");
      CHECK(worst_identity <= 1e-6);
    };
    {
      // The ring's profile, as a Precitech in PVT mode cuts it at one feed.
      const double eps = 1e-4, R = 0.2;
      const ProfileOptions o = ring_profile(eps, R, Interpolation::kCubic);
      const auto cls =
          compensated(ring, R, [&](ContactSink& sink) { plan_profile(ring, o, sink); });
      judge(ring, cls, R, eps, "profile");
    }
    {
      // A spiral through the vertex of the decentred sphere: slope on the axis, X through 0.
      const TransformedSurface& sphere = decentred_sphere;
      const double eps = 5e-4, R = 0.5;
      const SpiralOptions o = sphere_spiral(0.0, eps, R, Interpolation::kCubic);
      const auto cls = compensated(sphere, R, [&](ContactSink& sink) {
        plan_spiral(sphere, BaseSurface::plane(1.0), o, sink);
      });
      judge(sphere, cls, R, eps, "spiral through the vertex");
    }
    {
      // The same spiral with every seam's later band planned again from the seam's blocks
      // (the path a seam whose segments miss the target takes; none does here). The cubics
      // either side of each seam are then judged with both bands known, on any thread count.
      const TransformedSurface& sphere = decentred_sphere;
      const double eps = 5e-4, R = 0.5;
      SpiralOptions o = sphere_spiral(0.0, eps, R, Interpolation::kCubic);
      o.replan_every_seam = true;
      PathSummary one, two;
      const auto cls = compensated(sphere, R, [&](ContactSink& sink) {
        one = plan_spiral(sphere, BaseSurface::plane(1.0), o, sink);
      });
      o.threads = 2;
      ContactCollector on_two;
      two = plan_spiral(sphere, BaseSurface::plane(1.0), o, on_two);
      CHECK(one.replanned_seams >= 10);
      CHECK(two.replanned_seams == one.replanned_seams);
      REQUIRE(on_two.points.size() == cls.size());
      for (std::size_t i = 0; i < cls.size(); ++i) {
        CHECK(on_two.points[i].point == cls[i].contact.point);
        CHECK(on_two.points[i].chord_error == cls[i].contact.chord_error);
      }
      // The planner's figure at a segment that dips toward the design is the band's
      // (stand-off plus the dip below the band's centre), more than its distance from the
      // design, which is what the sampler measures: so no more than ε, and no less than
      // the sampler's worst.
      const test::DenseNoseFigures f =
          test::dense_nose_figures(sphere, cls, R, 100, 400, nullptr, true);
      double planned = 0;
      for (const CutterLocation& cl : cls) planned = std::max(planned, cl.contact.chord_error);
      MESSAGE("every seam planned again: ε " << eps * 1e6 << " nm, PVT motion " << f.worst * 1e6
                                             << " nm, planned " << planned * 1e6 << " nm, "
                                             << one.replanned_seams << " seams");
      CHECK(f.worst <= 1.002 * eps);
      CHECK(f.gouge <= 1e-9);
      CHECK(planned <= eps);
      CHECK(planned >= 0.99 * f.worst);
    }
    for (const CutterPointRule rule :
         {CutterPointRule::kEqualAngle, CutterPointRule::kEqualArcLength}) {
      // Equal angles and equal arc lengths under PVT, in bands of a turn (19 seams): the
      // blocks do not depend on the errors, and each segment's error, the seams' included,
      // is the one on the cubics through the blocks as placed. Checked segment by segment
      // against the dense sampler. The planner's figure is the band's: the stand-off s plus
      // the largest departure from the band's centre either way, so from the sampled
      // distances above the design, max(highest, 2s − lowest). Equal angles this coarse
      // (40 a turn) leave the design by up to 18 µm either way: the verdict's business,
      // not this test's.
      const TransformedSurface& sphere = decentred_sphere;
      const double eps = 5e-4, R = 0.5;
      SpiralOptions o = sphere_spiral(0.0, eps, R, Interpolation::kCubic);
      o.points.rule = rule;
      o.points.points_per_revolution = 40;
      o.points.arc_length = 0.05;
      const auto cls = compensated(sphere, R, [&](ContactSink& sink) {
        plan_spiral(sphere, BaseSurface::plane(1.0), o, sink);
      });
      o.threads = 2;
      ContactCollector on_two;
      plan_spiral(sphere, BaseSurface::plane(1.0), o, on_two);
      REQUIRE(on_two.points.size() == cls.size());
      bool same = true;
      for (std::size_t i = 0; i < cls.size(); ++i)
        same = same && on_two.points[i].point == cls[i].contact.point &&
               on_two.points[i].chord_error == cls[i].contact.chord_error;
      CHECK(same);
      double lowest_ratio = 1e300, highest_ratio = 0;
      for (std::size_t k = 1; k < cls.size(); ++k) {
        const test::DenseNoseFigures f =
            test::dense_nose_figures(sphere, cls, R, 40, 200, nullptr, true, k);
        const double s = cls[k].contact.stand_off;
        const double band = std::max(f.highest, 2 * s - f.lowest);
        lowest_ratio = std::min(lowest_ratio, cls[k].contact.chord_error / band);
        highest_ratio = std::max(highest_ratio, cls[k].contact.chord_error / band);
      }
      MESSAGE(
          std::string(rule == CutterPointRule::kEqualAngle ? "equal angles" : "equal arc lengths")
          << ", PVT in bands: " << cls.size() << " points, planned/sampled per segment in ["
          << lowest_ratio << ", " << highest_ratio << "]");
      CHECK(lowest_ratio >= 0.99);
      // The planner measures along the normal of the radial section, the sampler along
      // the surface's: the two differ by √(1 + f_t²), f_t the slope across the section,
      // here up to 8/√(30² − 9²) = 0.2795 (a factor of 1.038).
      CHECK(highest_ratio <= 1.01 * std::sqrt(1 + 0.2795 * 0.2795));
    }
  }

  TEST_CASE("PVT through a crease: every peak searched, and no block of no time") {
    // Blocks closer than the program's resolution (1 nm in X and Z): in profile mode a
    // block's time is its X-Z chord, so such a block has none.
    const auto still_blocks = [](const std::vector<CutterLocation>& cls) {
      int still = 0;
      for (std::size_t k = 1; k < cls.size(); ++k)
        if (std::hypot(cls[k].x - cls[k - 1].x, cls[k].z - cls[k - 1].z) <= 1e-6) ++still;
      return still;
    };
    const auto held_points = [](const std::vector<CutterLocation>& cls) {
      int held = 0;
      for (const CutterLocation& cl : cls) held += cl.contact.uncut_residual > 0;
      return held;
    };
    {
      // The ring's profile to its centre, where it meets its mirror image in a cone point
      // (slope Aω = 0.157): a 0.2 mm nose is held there, touching both flanks, from a
      // contact R·sin(atan 0.157) = 31 µm out, and stays still to the end.
      const double eps = 1e-4, R = 0.2;
      ProfileOptions o = ring_profile(eps, R, Interpolation::kCubic);
      o.inner_radius = 0;
      const auto cls =
          compensated(ring, R, [&](ContactSink& sink) { plan_profile(ring, o, sink); });
      const test::DenseNoseFigures f =
          test::dense_nose_figures(ring, cls, R, 200, 400, nullptr, true);
      double planned = 0;
      for (const CutterLocation& cl : cls) planned = std::max(planned, cl.contact.chord_error);
      MESSAGE("ring profile to the cone point, PVT: ε "
              << eps * 1e6 << " nm, PVT motion " << f.worst * 1e6 << " nm, planned "
              << planned * 1e6 << " nm, " << cls.size() << " points, " << held_points(cls)
              << " held");
      CHECK(held_points(cls) >= 1);
      CHECK(f.worst <= 1.002 * eps);
      CHECK(f.gouge <= 1e-9);
      CHECK(planned <= eps);
      CHECK(still_blocks(cls) == 0);
      // The held nose's centre stands on the axis: the last block's X is 0 to rounding.
      CHECK(std::abs(cls.back().x) <= 1e-9);
    }
    {
      // A ring whose cone point takes a 0.6 mm nose far from the axis (slope Aω = 0.314,
      // the hold from 0.18 mm out): a long stretch still at the centre, which blocks of no
      // length would have repeated (a gouging job elsewhere: its troughs are tighter than
      // the nose, which the checks, off here, report).
      const SinusoidalRing steep(0.05, 2 * std::numbers::pi, 0.0);
      const double eps = 1e-4, R = 0.6;
      ProfileOptions o = ring_profile(eps, R, Interpolation::kCubic);
      o.inner_radius = 0;
      const auto cls =
          compensated(steep, R, [&](ContactSink& sink) { plan_profile(steep, o, sink); });
      MESSAGE("steep ring to the cone point, PVT: " << cls.size() << " points, " << held_points(cls)
                                                    << " held, " << still_blocks(cls)
                                                    << " blocks of no length");
      CHECK(held_points(cls) >= 1);
      CHECK(still_blocks(cls) == 0);
      CHECK(std::abs(cls.back().x) <= 1e-9);
    }
  }

  TEST_CASE("PVT where no step meets the tolerance: the error linear motion gives, not slivers") {
    // A 1 mm nose in troughs of concave radius 1/(Aω²) = 0.507 mm: past r = 1.04 mm its
    // centre turns back, and no step meets ε. Linear motion stops there with an input
    // error; PVT took the least error of its slivers (3e-12 of τ, still) and crawled on
    // them without end. Both now name the same place.
    const SinusoidalRing steep(0.05, 2 * std::numbers::pi, 0.0);
    for (const Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
      ProfileOptions o = ring_profile(1e-4, 1.0, mode);
      o.outer_radius = 3.0;
      o.inner_radius = 0;
      ContactCollector sink;
      std::string message;
      try {
        plan_profile(steep, o, sink);
      } catch (const InputError& e) {
        message = e.what();
      }
      MESSAGE(std::string(mode == Interpolation::kLinear ? "linear: " : "PVT: ") << message);
      CHECK(message.find("cannot meet the chord tolerance 0.1 µm") != std::string::npos);
      CHECK(message.find("r = 1.04") != std::string::npos);
      // And why: its troughs curve to 1/(Aω²) = 0.5066 mm; the tightest of the samples
      // across the nose lies within 0.3 % of it.
      const std::size_t at = message.find("concave radius of ");
      REQUIRE(at != std::string::npos);
      const double radius = std::stod(message.substr(at + 18));
      CHECK(radius >= 1 / (0.05 * 4 * std::numbers::pi * std::numbers::pi));
      CHECK(radius <= 1.003 / (0.05 * 4 * std::numbers::pi * std::numbers::pi));
    }
  }

  TEST_CASE(
      "with B following about a pivot, ε holds on the pivot's motion, where the nose swings on "
      "arcs") {
    // An Alvarez plate (paper 002's 4-axis part): its slope changes around the turn, so B
    // does, and the nose centre swings on an arc of radius L between blocks.
    const Alvarez plate(0.02, 0.0);
    const double eps = 2e-4, R = 0.5, L = 60;
    CompensationOptions c;
    c.b_mode = BMode::kFollow;
    c.pivot_distance = L;
    SpiralOptions o = nose_spiral(3.0, 1.0, 0.1, eps, R);
    o.tool.axis_offset = L;
    o.tool.b_follows = true;
    c.tool.nose_radius = R;
    const auto cls = compensated(
        plate, R, [&](ContactSink& sink) { plan_spiral(plate, BaseSurface::plane(3.0), o, sink); },
        c);
    const double pivot = test::densest_nose_error(plate, cls, R, 50, 400, &c);
    const double centre = test::densest_nose_error(plate, cls, R);
    MESSAGE("ε " << eps * 1e6 << " nm: pivot motion " << pivot * 1e6
                 << " nm (a linear nose centre would err " << centre * 1e6 << " nm), " << cls.size()
                 << " points");
    CHECK(pivot <= 1.002 * eps);
    CHECK(pivot >= 0.9 * eps);
    // Planned as if the centre moved linearly, the same tolerance errs more on the pivot.
    SpiralOptions naive = o;
    naive.tool.axis_offset = 0;
    const auto naive_cls = compensated(
        plate, R,
        [&](ContactSink& sink) { plan_spiral(plate, BaseSurface::plane(3.0), naive, sink); }, c);
    CHECK(test::densest_nose_error(plate, naive_cls, R, 50, 400, &c) > 1.2 * eps);
  }
}
