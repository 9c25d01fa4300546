#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/height_field_queries.hpp"
#include "freeturn/surface/sinusoidal.hpp"

using namespace freeturn;

namespace {

// Reference closest point: a dense 201 × 201 sample of (x, y) within 1.2 mm of p's
// footprint, then a compass search (halving the step when no neighbour is closer).
double reference_distance(const Surface& s, const Eigen::Vector3d& p) {
  double best = INFINITY, bx = 0, by = 0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const double x = p.x() - 1.2 + 2.4 * i / 200, y = p.y() - 1.2 + 2.4 * j / 200;
      const double d = (s.point(x, y) - p).norm();
      if (d < best) best = d, bx = x, by = y;
    }
  for (double h = 0.012; h > 1e-13;) {
    double nx = bx, ny = by;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b) {
        const double d = (s.point(bx + a * h, by + b * h) - p).norm();
        if (d < best) best = d, nx = bx + a * h, ny = by + b * h;
      }
    if (nx == bx && ny == by) h *= 0.5;
    bx = nx;
    by = ny;
  }
  return best;
}

}  // namespace

TEST_SUITE("surface") {
  TEST_CASE("height-field closest point agrees with dense sampling to 1e-9 mm") {
    std::array<double, 9> a{};
    a[0] = 2e-5;
    const EvenAsphere asphere(1 / 30.0, -0.7, a);
    const SinusoidalGrid grid(0.002, 4.0, 6.0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> xy(-8, 8), off(-0.5, 0.5);
    for (const Surface* s :
         {static_cast<const Surface*>(&asphere), static_cast<const Surface*>(&grid)}) {
      double worst = 0;
      for (int k = 0; k < 40; ++k) {
        const double x = xy(rng), y = xy(rng);
        const Eigen::Vector3d p = s->point(x, y) + Eigen::Vector3d(off(rng), off(rng), off(rng));
        const auto r = closest_point(*s, p);
        CHECK(r.status == Status::kOk);
        worst = std::max(worst, std::abs(r.distance - reference_distance(*s, p)));
        CHECK(std::abs(r.point.z() - s->sag(r.point.x(), r.point.y())) <= 1e-15);
      }
      MESSAGE(std::string(s->type()) << ": worst |distance - reference| = " << worst << " mm");
      CHECK(worst <= 1e-9);
    }
  }

  TEST_CASE("height-field ray intersection: a sphere in closed form, warm starts, misses") {
    const double R = 20.0;
    const EvenAsphere sphere(1 / R, 0.0);
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> xy(-10, 10), tilt(-0.4, 0.4);
    double t_prev = NAN;
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d origin(xy(rng), xy(rng), 5.0);
      const Eigen::Vector3d dir = Eigen::Vector3d(tilt(rng), tilt(rng), -1).normalized();
      // Closed form: |origin + t·dir − (0, 0, R)| = R; the origin is inside the sphere, so
      // the lower cap (the vertex side) is the positive root.
      const Eigen::Vector3d w = origin - Eigen::Vector3d(0, 0, R);
      const double b = w.dot(dir), c = w.squaredNorm() - R * R;
      const double t_exact = -b + std::sqrt(b * b - c);
      const auto hit = intersect_ray(sphere, origin, 3.0 * dir);
      CHECK(hit.status == Status::kOk);
      CHECK(hit.t == doctest::Approx(t_exact / 3.0).epsilon(1e-12));
      const auto warm = intersect_ray(sphere, origin, dir, std::isnan(t_prev) ? 0.0 : t_prev);
      CHECK(warm.t == doctest::Approx(t_exact).epsilon(1e-12));
      CHECK((hit.point - (origin + t_exact * dir)).norm() <= 1e-10);
      // The gradient at the hit, which the planner takes instead of evaluating it again:
      // the sphere's z = R − √(R² − s) has ∇z = (x, y)/√(R² − s) at the exact hit.
      const Eigen::Vector3d exact = origin + t_exact * dir;
      const double root = std::sqrt(R * R - exact.x() * exact.x() - exact.y() * exact.y());
      CHECK(hit.zx == doctest::Approx(exact.x() / root).epsilon(1e-10));
      CHECK(hit.zy == doctest::Approx(exact.y() / root).epsilon(1e-10));
      t_prev = warm.t;
    }
    // Past the edge of the sphere the sag is undefined: the ray misses.
    CHECK(intersect_ray(sphere, {30, 0, 5}, {0, 0, -1}).status == Status::kMissed);
    CHECK(intersect_ray(sphere, {0, 0, 5}, {0, 0, 0}).status == Status::kDegenerate);
  }
}
