#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/surface/conic.hpp"
#include "freeturn/surface/jet.hpp"
#include "freeturn/surface/lenslet_array.hpp"

using namespace freeturn;
using Pattern = LensletArrayOptions::Pattern;

namespace {

LensletArrayOptions eye(Pattern pattern) {
  LensletArrayOptions o;
  o.base_curvature = 1 / 20.0;  // base sphere R 20 mm
  o.lens_radius = -1.5;         // convex lenslets (centre toward −z)
  o.lens_diameter = 0.9;
  o.pitch = 1.0;
  o.pattern = pattern;
  o.extent = 6.0;
  return o;
}

// The lenslet holding (x, y) by scanning every lenslet (independent of the lookup grid).
int scan(const LensletArray& s, const LensletArrayOptions& o, double x, double y) {
  const double c = o.base_curvature;
  const double r2 = x * x + y * y;
  const Eigen::Vector3d base(x, y, c * r2 / (1 + std::sqrt(1 - c * c * r2)));
  for (int i = 0; i < s.lenslet_count(); ++i) {
    const Eigen::Vector3d axis = s.lenslet_axis(i);
    // The base point of lenslet i is where its axis meets the base.
    const Eigen::Vector3d w = base - s.lenslet_vertex(i);
    if ((w - w.dot(axis) * axis).norm() < 0.5 * o.lens_diameter) return i;
  }
  return -1;
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("compound eye: lenslets on the base sphere, axes through its centre, lookup = scan") {
    for (Pattern pattern : {Pattern::kRings, Pattern::kHexagonal}) {
      const LensletArrayOptions o = eye(pattern);
      const LensletArray s(o);
      CHECK(std::string(s.type()) == "compound_eye");
      CHECK(s.lenslet_count() > 50);
      for (int i = 0; i < s.lenslet_count(); ++i) {
        // The axis passes through the base sphere's centre (0, 0, 20).
        const Eigen::Vector3d v = s.lenslet_vertex(i), a = s.lenslet_axis(i);
        const Eigen::Vector3d to_centre = Eigen::Vector3d(0, 0, 20) - v;
        CHECK((to_centre - to_centre.dot(a) * a).norm() <= 1e-12);
        // At the vertex: the sag is the vertex, the normal the axis.
        CHECK(s.sag(v.x(), v.y()) == doctest::Approx(v.z()).epsilon(1e-13).scale(1e-13));
        CHECK((s.normal(v.x(), v.y()) - a).norm() <= 1e-12);
      }
      std::mt19937 rng(3);
      std::uniform_real_distribution<double> u(-6, 6);
      for (int k = 0; k < 3000; ++k) {
        const double x = u(rng), y = u(rng);
        CHECK(s.lenslet_at(x, y) == scan(s, o, x, y));
      }
    }
  }

  TEST_CASE("lenslet arrays: the lookup beside a rim = scan, from 10 nm to 0.1 mm off it") {
    // lenslet_at tries the lenslet it found last first, then the lenslets its fine grid's
    // cell lists. Points just either side of each rim a radial line crosses (the crossings
    // in closed form), and along the rest of the line, must find the lenslet the scan
    // finds: the random points above seldom come this close to a rim.
    LensletArrayOptions plane = eye(Pattern::kSquare);
    plane.base_curvature = 0;
    LensletArrayOptions shallow = eye(Pattern::kHexagonal);
    shallow.lens_diameter = 0.2;  // small lenslets far apart: wide stretches of base
    for (const LensletArrayOptions& o : {eye(Pattern::kRings), shallow, plane}) {
      const LensletArray s(o);
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
      long beside = 0, on_lenslets = 0;
      for (int line = 0; line < 40; ++line) {
        const RadialLine l(angle(rng));
        std::array<double, 64> found{};
        const int n = s.section_creases(l, 0.0, 5.5, found);
        REQUIRE(n >= 0);
        REQUIRE(n < 64);
        for (int k = 0; k < n; ++k)
          for (const double off : {1e-5, 1e-4, 1e-3, 1e-2, 1e-1})
            for (const double side : {-1.0, 1.0}) {
              const double rho = found[k] + side * off;
              const double x = rho * l.cos, y = rho * l.sin;
              CAPTURE(rho);
              CHECK(s.lenslet_at(x, y) == scan(s, o, x, y));
              ++beside;
            }
        for (double rho = 0; rho <= 5.5; rho += 1.3e-3) {
          const double x = rho * l.cos, y = rho * l.sin;
          const int at = s.lenslet_at(x, y);
          CHECK(at == scan(s, o, x, y));
          on_lenslets += at >= 0;
        }
      }
      CHECK(beside > 400);
      CHECK(on_lenslets > 1000);
    }
  }

  TEST_CASE("lenslet arrays: a radial line's creases are where its points change lenslet") {
    // The closed-form rim crossings (and the bound that skips far lenslets) against a walk
    // along the line: every change of lenslet_at (checked against the scan above) between
    // samples 0.5 µm apart, bisected to 1e-13 mm, is a reported crease, and every reported
    // crease separates two lenslets (or a lenslet and the base).
    LensletArrayOptions plane = eye(Pattern::kSquare);
    plane.base_curvature = 0;
    for (const LensletArrayOptions& o : {eye(Pattern::kRings), eye(Pattern::kHexagonal), plane}) {
      const LensletArray s(o);
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi), start(-5.5, 3.5),
          length(0.2, 2.0);
      long crossings = 0;
      for (int line = 0; line < 60; ++line) {
        const double theta = angle(rng), lo = start(rng), hi = lo + length(rng);
        const double ct = std::cos(theta), st = std::sin(theta);
        const auto at = [&](double rho) { return s.lenslet_at(rho * ct, rho * st); };
        std::array<double, 32> found{};
        const int n = s.section_creases(theta, lo, hi, found);
        REQUIRE(n < 32);
        for (int k = 1; k < n; ++k) CHECK(found[k - 1] < found[k]);
        const auto reported = [&](double rho) {
          for (int k = 0; k < n; ++k)
            if (std::abs(found[k] - rho) <= 1e-9) return true;
          return false;
        };
        constexpr double kStep = 5e-4;
        int walked = 0;
        for (double a = lo; a < hi; a += kStep) {
          double b = std::min(hi, a + kStep);
          int ia = at(a);
          if (ia == at(b)) continue;
          double left = a;
          while (b - left > 1e-13) {
            const double mid = 0.5 * (left + b);
            (at(mid) == ia ? left : b) = mid;
          }
          CAPTURE(theta);
          CAPTURE(left);
          CHECK(reported(left));
          ++walked;
        }
        for (int k = 0; k < n; ++k) {
          CAPTURE(found[k]);
          CHECK(at(found[k] - 1e-8) != at(found[k] + 1e-8));
        }
        CHECK(walked <= n);
        crossings += n;
      }
      CHECK(crossings > 60);  // the lines do cross rims
    }
  }

  TEST_CASE("lenslet arrays: a path's consecutive crease queries agree with cold ones") {
    // section_creases keeps, per thread, the lenslets near the last stretch it was asked
    // about, and answers a nearby stretch from that list. Along a spiral-like walk of
    // stretches (0.3° and 2 µm apart, ±0.4 mm about the contact) each warm answer must
    // equal, bit for bit, the answer to the same stretch asked cold (another array asked
    // in between takes the thread's list, so the next query rebuilds it), and every
    // tenth is walked as above. A copy of the array keeps its own list.
    const LensletArray a(eye(Pattern::kRings));
    const LensletArray b(eye(Pattern::kHexagonal));
    const LensletArray copy = a;
    long compared = 0, crossings = 0;
    double rho = 5.2, theta = 0.3;
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int k = 0; k < 6000; ++k, theta += 0.3 * std::numbers::pi / 180, rho -= 2e-4) {
      const RadialLine line(theta);
      std::array<double, 32> warm{}, cold{}, other{}, copied{};
      // A stretch beside this one first, up to 0.1 rad and 0.3 mm away: the query after
      // it is answered from its list where that covers it, and rebuilds it where not.
      a.section_creases(RadialLine(theta - 0.1 * unit(rng)), rho - 0.4 + 0.3 * unit(rng),
                        rho + 0.4 + 0.3 * unit(rng), warm);
      const int n_warm = a.section_creases(line, rho - 0.4, rho + 0.4, warm);
      b.section_creases(line, rho - 0.4, rho + 0.4, other);  // takes the thread's list
      const int n_cold = a.section_creases(line, rho - 0.4, rho + 0.4, cold);
      const int n_copy = copy.section_creases(line, rho - 0.4, rho + 0.4, copied);
      REQUIRE(n_warm == n_cold);
      REQUIRE(n_copy == n_cold);
      for (int j = 0; j < n_warm; ++j) {
        CHECK(warm[j] == cold[j]);
        CHECK(copied[j] == cold[j]);
      }
      ++compared;
      crossings += n_warm;
      if (k % 10 != 0) continue;
      const auto at = [&](double r) { return a.lenslet_at(r * line.cos, r * line.sin); };
      for (double x = rho - 0.4; x < rho + 0.4; x += 5e-4) {
        const double y = std::min(rho + 0.4, x + 5e-4);
        if (at(x) == at(y)) continue;
        bool reported = false;
        for (int j = 0; j < n_cold; ++j) reported = reported || (cold[j] >= x - 1e-9 && cold[j] <= y + 1e-9);
        CAPTURE(theta);
        CAPTURE(x);
        CHECK(reported);
      }
    }
    CHECK(compared == 6000);
    CHECK(crossings > 3000);
  }

  TEST_CASE("compound eye: lens points on their sphere, continuous at every rim") {
    const LensletArrayOptions o = eye(Pattern::kRings);
    const LensletArray s(o);
    for (int i = 0; i < s.lenslet_count(); i += 7) {
      const Eigen::Vector3d v = s.lenslet_vertex(i), a = s.lenslet_axis(i);
      const Eigen::Vector3d centre = v + o.lens_radius * a;
      // Walk outward from the vertex across the rim, in the direction of +x.
      const Eigen::Vector3d side = a.cross(Eigen::Vector3d::UnitY()).normalized();
      double last_inside = NAN, first_outside = NAN;
      for (int k = 0; k <= 2000; ++k) {
        const Eigen::Vector3d q = v + side * (0.7 * o.lens_diameter * k / 2000);
        const Eigen::Vector3d p = s.point(q.x(), q.y());
        if (s.lenslet_at(q.x(), q.y()) == i) {
          CHECK(std::abs((p - centre).norm() - std::abs(o.lens_radius)) <= 1e-12);
          last_inside = p.z();
        } else if (std::isnan(first_outside)) {
          first_outside = p.z();
        }
      }
      // Step 0.7·D/2000 ≈ 3e-4 mm with slopes below 1: the jump at the rim is the step's
      // rise alone; a misplaced vertex height would show as a step of micrometres.
      CHECK(std::abs(first_outside - last_inside) <= 5e-4);
    }
  }

  TEST_CASE("lenslet surfaces: gradient and Hessian by finite differences away from rims") {
    for (const LensletArrayOptions& o : {eye(Pattern::kHexagonal), [] {
                                           LensletArrayOptions m = eye(Pattern::kSquare);
                                           m.base_curvature = 0;
                                           return m;
                                         }()}) {
      const LensletArray s(o);
      std::mt19937 rng(9);
      std::uniform_real_distribution<double> u(-5.5, 5.5);
      const double h = 1e-5;
      int checked = 0;
      for (int k = 0; k < 400 && checked < 100; ++k) {
        const double x = u(rng), y = u(rng);
        const int at = s.lenslet_at(x, y);
        bool same = true;
        for (double dx : {-h, 0.0, h})
          for (double dy : {-h, 0.0, h}) same = same && s.lenslet_at(x + dx, y + dy) == at;
        if (!same) continue;
        ++checked;
        const auto d = s.height_derivatives(x, y);
        const auto px = s.height_derivatives(x + h, y), mx = s.height_derivatives(x - h, y);
        const auto py = s.height_derivatives(x, y + h), my = s.height_derivatives(x, y - h);
        CHECK(d.zx == doctest::Approx((px.z - mx.z) / (2 * h)).epsilon(1e-6).scale(1e-6));
        CHECK(d.zy == doctest::Approx((py.z - my.z) / (2 * h)).epsilon(1e-6).scale(1e-6));
        CHECK(d.zxx == doctest::Approx((px.zx - mx.zx) / (2 * h)).epsilon(1e-5).scale(1e-4));
        CHECK(d.zxy == doctest::Approx((py.zx - my.zx) / (2 * h)).epsilon(1e-5).scale(1e-4));
        CHECK(d.zyy == doctest::Approx((py.zy - my.zy) / (2 * h)).epsilon(1e-5).scale(1e-4));
      }
      CHECK(checked == 100);
    }
  }

  TEST_CASE("lenslet surfaces: the Hessian's closed form gives the bits of the jets' formula") {
    // height_derivatives writes the chain rule out by hand; the same spheres written once
    // with Jet<2> (the lens sphere about vertex + R·axis, the base conic) must give the same
    // doubles, on lenslets, on the base, on domes and bowls, on a sphere and on a plane.
    std::vector<LensletArrayOptions> arrays = {eye(Pattern::kRings), eye(Pattern::kHexagonal)};
    arrays.push_back(eye(Pattern::kSquare));
    arrays.back().base_curvature = 0;
    arrays.push_back(eye(Pattern::kRings));
    arrays.back().lens_radius = 2.0;  // bowls
    arrays.push_back(eye(Pattern::kHexagonal));
    arrays.back().base_curvature = -1 / 15.0;
    for (const LensletArrayOptions& o : arrays) {
      const LensletArray s(o);
      std::mt19937 rng(17);
      std::uniform_real_distribution<double> u(-6.0, 6.0);
      int on_lenslets = 0, on_base = 0;
      for (int k = 0; k < 4000; ++k) {
        const double x = u(rng), y = u(rng);
        using J = Jet<2>;
        const J X = J::variable_x(x), Y = J::variable_y(y);
        const int i = s.lenslet_at(x, y);
        J z;
        if (i < 0) {
          z = conic_sag(o.base_curvature, 0.0, X * X + Y * Y);
          ++on_base;
        } else {
          const Eigen::Vector3d c = s.lenslet_vertex(i) + o.lens_radius * s.lenslet_axis(i);
          const J dx = X - c.x(), dy = Y - c.y();
          const double r = o.lens_radius;
          z = c.z() - (r > 0 ? 1.0 : -1.0) * sqrt(r * r - dx * dx - dy * dy);
          ++on_lenslets;
        }
        const HeightDerivatives h = s.height_derivatives(x, y);
        const double expected[6] = {z.v, z.dx, z.dy, z.dxx, z.dxy, z.dyy};
        const double got[6] = {h.z, h.zx, h.zy, h.zxx, h.zxy, h.zyy};
        for (int j = 0; j < 6; ++j) {
          INFO("x = ", x, ", y = ", y, ", component ", j);
          CHECK((got[j] == expected[j] || (std::isnan(got[j]) && std::isnan(expected[j]))));
        }
      }
      CHECK(on_lenslets > 1000);
      CHECK(on_base > 1000);
    }
  }

  TEST_CASE("lenslet arrays: max_bend bounds every section's second derivative") {
    // The bound the nose's crease searches rely on (Surface::max_bend): at random points
    // within a radius, along random directions, the second difference of the sag (the
    // three points on one lenslet or all on the base) stays under it. Domes and bowls on
    // concave and convex bases, and a plane base. The bound is also not loose: the
    // largest second difference found comes within a fifth of it where bowls or a
    // concave base set it (their bends peak at the footprints' far edges and at the
    // radius, where the samples reach).
    struct Case {
      double base_curvature, lens_radius;
    };
    for (const Case c : {Case{1 / 20.0, -1.5}, Case{1 / 20.0, 1.5}, Case{-1 / 20.0, 1.5},
                         Case{-1 / 20.0, -1.5}, Case{0.0, 1.5}}) {
      LensletArrayOptions o = eye(Pattern::kHexagonal);
      o.base_curvature = c.base_curvature;
      o.lens_radius = c.lens_radius;
      const LensletArray s(o);
      const double radius = 5.5, bound = s.max_bend(radius);
      REQUIRE(std::isfinite(bound));
      CHECK(s.max_bend(2.0) <= bound);  // a smaller disc bends no more
      std::mt19937 rng(17);
      std::uniform_real_distribution<double> unit(0, 1);
      const double h = 1e-4;
      double largest = -1e300;
      int checked = 0, over = 0;
      for (int k = 0; k < 200000; ++k) {
        const double r = radius * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
        const double dir = 2 * std::numbers::pi * unit(rng);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        const double ux = std::cos(dir), uy = std::sin(dir);
        if (std::hypot(x + h * ux, y + h * uy) > radius || std::hypot(x - h * ux, y - h * uy) > radius)
          continue;
        const int at = s.lenslet_at(x, y);
        if (s.lenslet_at(x + h * ux, y + h * uy) != at || s.lenslet_at(x - h * ux, y - h * uy) != at)
          continue;
        const double bend = (s.sag(x + h * ux, y + h * uy) - 2 * s.sag(x, y) +
                             s.sag(x - h * ux, y - h * uy)) / (h * h);
        ++checked;
        largest = std::max(largest, bend);
        // Rounding of the second difference: ~4·1e-16·|z|/h² with |z| ≤ 1 mm.
        over += bend > bound + 1e-7;
      }
      MESSAGE("bound ", bound, " mm⁻¹, largest second difference ", largest);
      CHECK(over == 0);
      CHECK(checked > 150000);
      if (c.lens_radius > 0 || c.base_curvature > 0) CHECK(largest >= 0.8 * bound);
      else CHECK(bound == 0.0);
    }
  }

  TEST_CASE("lenslet arrays: creases_near bounds every rim a half-line from the point meets") {
    // Brute force apart from the bounds' geometry: from random points, 180 half-lines are
    // marched in 2 µm steps up to the radius, each change of lenslet (lenslet_at) bisected
    // to 1e-12 mm. Every crossing must belong to a reported crease (the lenslet entered or
    // left) no nearer than its reported distance, with a slope jump along the half-line (the
    // gradient either side, 1e-8 mm off) within the reported bound, and a half-line must
    // cross no rim more often than reported. The nearest distance is also not loose: within
    // 5 % of the nearest crossing found, where one is found. Domes and bowls on convex and
    // concave bases, and a plane base.
    struct Case {
      double base_curvature, lens_radius;
    };
    for (const Case c :
         {Case{1 / 20.0, -5.0}, Case{1 / 20.0, 1.5}, Case{-1 / 20.0, -1.5}, Case{0.0, 1.5}}) {
      CAPTURE(c.base_curvature);
      CAPTURE(c.lens_radius);
      LensletArrayOptions o = eye(Pattern::kRings);
      o.base_curvature = c.base_curvature;
      o.lens_radius = c.lens_radius;
      o.extent = 3.0;
      const LensletArray s(o);
      const double radius = 0.4;
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> unit(0, 1);
      int crossings = 0, points_near = 0, over = 0;
      double loosest = 1;
      for (int k = 0; k < 60; ++k) {
        const double r = 2.4 * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        std::array<NearbyCrease, 16> near;
        const int count = s.creases_near(x, y, radius, near);
        REQUIRE(count >= 0);
        // A report does not say which lenslet it is: each crossing is matched with any
        // report that covers it.
        double nearest = 1e300;
        for (int d = 0; d < 180; ++d) {
          const double angle = 2 * std::numbers::pi * d / 180;
          const double ux = std::cos(angle), uy = std::sin(angle);
          const auto at = [&](double t) { return s.lenslet_at(x + t * ux, y + t * uy); };
          std::vector<int> times(static_cast<std::size_t>(s.lenslet_count()), 0);
          int before = at(0);
          for (double t = 2e-3; t <= radius + 1e-12; t += 2e-3) {
            const int now = at(t);
            if (now == before) continue;
            double lo = t - 2e-3, hi = t;
            while (hi - lo > 1e-12) {
              const double mid = 0.5 * (lo + hi);
              (at(mid) == before ? lo : hi) = mid;
            }
            // The gradient's jump: along the half-line, and its direction in (x, y) (the
            // rim's normal, up to sign).
            double jump_x, jump_y;
            {
              double z, zx, zy, z2, zx2, zy2;
              s.sag_gradient(x + (lo - 1e-8) * ux, y + (lo - 1e-8) * uy, z, zx, zy);
              s.sag_gradient(x + (hi + 1e-8) * ux, y + (hi + 1e-8) * uy, z2, zx2, zy2);
              jump_x = zx2 - zx;
              jump_y = zy2 - zy;
            }
            const double slope_jump = std::abs(jump_x * ux + jump_y * uy);
            const double jump_norm = std::hypot(jump_x, jump_y);
            ++crossings;
            nearest = std::min(nearest, hi);
            // The rim crossed is the lenslet left (before ≥ 0) or entered (now ≥ 0).
            for (const int lenslet : {before, now})
              if (lenslet >= 0) ++times[static_cast<std::size_t>(lenslet)];
            // A report that tells its rim's directions must hold the rim's normal here
            // within asin(|q − T|/|T − e|) + its slack of its direction from the centre e
            // to the point (the normal leans from the direction from e to q by the slack
            // at most, and q is seen from e within that arcsine of T).
            const auto direction_holds = [&](const NearbyCrease& c) {
              if (!(c.centre_distance > 0)) return true;
              const double seen = hi < c.centre_distance ? std::asin(hi / c.centre_distance)
                                                         : 0.5 * std::numbers::pi;
              const double cosine = std::abs(jump_x * c.normal_x + jump_y * c.normal_y) / jump_norm;
              const double angle = std::acos(std::min(1.0, cosine));
              return angle <= seen + c.normal_slack + 1e-6;
            };
            bool covered = false;
            for (int q = 0; q < count; ++q)
              covered =
                  covered || (near[q].distance <= hi + 1e-9 &&
                              near[q].slope_jump >= slope_jump - 1e-6 && direction_holds(near[q]));
            over += !covered;
            before = now;
          }
          // No report allows fewer crossings than a rim showed.
          int most = 0;
          for (const int n : times) most = std::max(most, n);
          int allowed = 0;
          for (int q = 0; q < count; ++q) allowed = std::max(allowed, near[q].crossings);
          over += most > allowed;
        }
        if (nearest < radius) {
          ++points_near;
          double reported = 1e300;
          for (int q = 0; q < count; ++q) reported = std::min(reported, near[q].distance);
          CHECK(reported <= nearest + 1e-9);
          loosest = std::min(loosest, reported / nearest);
        }
      }
      MESSAGE("crossings ", crossings, ", points with a rim near ", points_near,
              ", nearest reported / found at worst ", loosest);
      // The rims' curvature against the reported bound: rims found by bisection along 720
      // rays from the centre each report names (the point less centre_distance along its
      // direction), and the circle through each three neighbours.
      double tightest = 0;
      int rims = 0;
      for (int k = 0; k < 8; ++k) {
        const double r = 2.2 * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        std::array<NearbyCrease, 16> near;
        const int count = s.creases_near(x, y, 0.3, near);
        REQUIRE(count >= 0);
        for (int q = 0; q < count; ++q) {
          const NearbyCrease& c = near[q];
          REQUIRE(c.centre_distance > 0);
          const double ex = x - c.centre_distance * c.normal_x;
          const double ey = y - c.centre_distance * c.normal_y;
          const int own = s.lenslet_at(ex, ey);
          REQUIRE(own >= 0);
          constexpr int kRays = 720;
          std::vector<Eigen::Vector2d> rim;
          for (int j = 0; j < kRays; ++j) {
            const double a = 2 * std::numbers::pi * j / kRays;
            double lo = 0, hi = 0.6;
            while (hi - lo > 1e-13) {
              const double mid = 0.5 * (lo + hi);
              (s.lenslet_at(ex + mid * std::cos(a), ey + mid * std::sin(a)) == own ? lo : hi) = mid;
            }
            rim.emplace_back(ex + lo * std::cos(a), ey + lo * std::sin(a));
          }
          for (int j = 0; j < kRays; ++j) {
            const Eigen::Vector2d &p0 = rim[static_cast<std::size_t>((j + kRays - 1) % kRays)],
                                  &p1 = rim[static_cast<std::size_t>(j)],
                                  &p2 = rim[static_cast<std::size_t>((j + 1) % kRays)];
            const double a = (p1 - p0).norm(), b = (p2 - p1).norm(), e = (p2 - p0).norm();
            const Eigen::Vector2d u = p1 - p0, v = p2 - p0;
            const double cross = std::abs(u.x() * v.y() - u.y() * v.x());
            const double curvature = 2 * cross / (a * b * e);  // 1 / circumradius
            tightest = std::max(tightest, curvature / c.curvature);
          }
          ++rims;
        }
      }
      MESSAGE("rims traced ", rims, ", curvature / bound at most ", tightest);
      CHECK(rims > 3);
      CHECK(tightest <= 1 + 1e-4);
      CHECK(tightest > 0.9);
      CHECK(over == 0);
      CHECK(crossings > 200);
      CHECK(points_near > 30);
      CHECK(loosest >= 0.95);
    }
  }

  TEST_CASE("lenslet arrays: creases_near knows nothing where footprints touch, or off the base") {
    // On a plane, footprints of the pitch's diameter touch: a rim there meets two lenses,
    // whose slopes the bound does not cover, so nothing is claimed (−1).
    LensletArrayOptions o = eye(Pattern::kHexagonal);
    o.base_curvature = 0;
    o.lens_diameter = o.pitch;
    std::array<NearbyCrease, 16> near;
    CHECK(LensletArray(o).creases_near(0.3, 0.2, 0.4, near) == -1);
    o.lens_diameter = 0.9 * o.pitch;
    CHECK(LensletArray(o).creases_near(0.3, 0.2, 0.4, near) >= 1);
    // Past the base sphere's rim (R_b = 20 mm) nothing is known.
    CHECK(LensletArray(eye(Pattern::kRings)).creases_near(25.0, 0.0, 0.4, near) == -1);
    // Too many creases for the buffer: −1, not a short list.
    CHECK(LensletArray(eye(Pattern::kRings))
              .creases_near(0.0, 0.0, 2.0, std::span<NearbyCrease>(near.data(), 2)) == -1);
  }

  TEST_CASE("microlens array on a plane: square lattice count and sag") {
    LensletArrayOptions o;
    o.lens_radius = 2.0;
    o.lens_diameter = 1.0;
    o.pitch = 1.2;
    o.pattern = Pattern::kSquare;
    o.extent = 5.0;
    const LensletArray s(o);
    CHECK(std::string(s.type()) == "microlens_array");
    // Lattice points (1.2 i, 1.2 j) with |·| ≤ 5 − 0.5 = 4.5: i² + j² ≤ 14.06 → 45.
    CHECK(s.lenslet_count() == 45);
    // Concave lens (R = 2, centre toward +z) dipping below the plane; rim at z = 0.
    const double rim = 2.0 - std::sqrt(4.0 - 0.25);
    CHECK(s.sag(0.0, 0.0) == doctest::Approx(-rim).epsilon(1e-14));
    CHECK(s.sag(0.3, 0.0) == doctest::Approx(-rim + 2.0 - std::sqrt(4.0 - 0.09)).epsilon(1e-14));
    CHECK(s.sag(0.6, 0.6) == 0.0);  // between lenslets: the plane
  }

  TEST_CASE("lenslet arrays refuse impossible geometry") {
    LensletArrayOptions o = eye(Pattern::kHexagonal);
    o.lens_diameter = 1.1;
    CHECK_THROWS_WITH_AS(
        LensletArray{o},
        "lens_diameter: a lenslet of diameter 1.1 mm is larger than its pitch 1 mm: "
        "neighbours would overlap",
        InputError);
    o = eye(Pattern::kHexagonal);
    o.lens_radius = 0.4;
    CHECK_THROWS_AS(LensletArray{o}, InputError);
    // A hemisphere (|R| = D/2): its wall is vertical at the rim, where its slope is
    // infinite. A hemispherical bowl's program had been written 6.9 µm into its wall.
    for (const double sign : {1.0, -1.0}) {
      o = eye(Pattern::kHexagonal);
      o.lens_radius = sign * 0.5 * o.lens_diameter;
      CHECK_THROWS_WITH_AS(LensletArray{o},
                           doctest::Contains("equals half the lens diameter: each lenslet would be "
                                             "a hemisphere"),
                           InputError);
      // A radius a hair larger has a finite wall (its slope D/2 / √(R² − D²/4) at the rim).
      o.lens_radius = sign * 0.5 * o.lens_diameter * (1 + 1e-9);
      const LensletArray steep(o);
      CHECK(steep.lenslet_count() > 0);
    }
  }
}
