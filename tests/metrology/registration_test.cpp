#include <doctest/doctest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <yaml-cpp/yaml.h>

#include "freeturn/core/error.hpp"
#include "freeturn/job/surface_yaml.hpp"
#include "freeturn/metrology/registration.hpp"
#include "freeturn/surface/zernike.hpp"

using namespace freeturn;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The demo's compound eye: lenslets on a sphere. Its lenslets pin the pose: a decentre or a
// clocking moves them, which no smooth error can mimic.
std::unique_ptr<Surface> compound_eye() {
  return surface_from_yaml(YAML::Load("{type: compound_eye, base_radius: 20.0, lens_radius: -5.0, "
                                      "lens_diameter: 0.9, pitch: 1.0, pattern: rings}"),
                           "<test>", 4.0);
}

// A known form error in the design's frame: astigmatism (Z6) 0.3 µm, trefoil (Z9) 0.2 µm,
// Z5 0.1 µm, over R_n = 4 mm.
std::vector<double> known_error() {
  std::vector<double> a(11, 0.0);
  a[4] = 0.1e-3;
  a[5] = 0.3e-3;
  a[8] = 0.2e-3;
  return a;
}

struct Pose {
  double piston = 5e-3, tilt_x = 1e-4, tilt_y = -0.7e-4, dx = 0.030, dy = -0.020,
         clocking = 0.5 * kDeg;
  Eigen::Matrix3d rotation() const {
    return (Eigen::AngleAxisd(clocking, Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(tilt_y, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(tilt_x, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
  }
};

// The part (design + error) measured in a frame moved by the pose's inverse, on a grid of
// `step` mm, with Gaussian noise of `noise` mm and `dropouts` of the points lost.
Measurement measure(const Surface& design, const Zernike& error, const Pose& pose, double step,
                    double noise, double dropouts) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss(0, noise);
  std::uniform_real_distribution<double> uniform(0, 1);
  const Eigen::Matrix3d r = pose.rotation();
  const Eigen::Vector3d t(pose.dx, pose.dy, pose.piston);
  Measurement m;
  for (double x = -3.9; x <= 3.9; x += step)
    for (double y = -3.9; y <= 3.9; y += step) {
      if (std::hypot(x, y) > 3.9) continue;
      if (uniform(random) < dropouts) {
        ++m.invalid;
        continue;
      }
      const Eigen::Vector3d q(x, y, design.sag(x, y) + error.sag(x, y) + gauss(random));
      m.points.push_back(r.transpose() * (q - t));
    }
  return m;
}

}  // namespace

TEST_SUITE("metrology") {
  TEST_CASE("a misregistered compound eye with astigmatism and trefoil: the pose and the error recovered") {
    const auto design = compound_eye();
    const Zernike error(0, 0, {}, 4.0, known_error());
    const Pose pose;
    const Measurement m = measure(*design, error, pose, 0.02, 1e-6, 0.05);
    RegistrationOptions o;
    o.zernike_terms = 21;
    o.normalization_radius = 4.0;
    o.outer_radius = 4.0;
    const Registration r = register_measurement(*design, m, o, "m.xyz");
    MESSAGE("iterations " << r.iterations << ", used " << r.used << ", outliers " << r.outliers
                          << ", fit RMS " << r.fit_rms * 1e6 << " nm");
    // The bounds: decentre to 0.5 µm, tilt to 1e-6 rad, clocking to 0.01°.
    CHECK(std::abs(r.decentre_x - pose.dx) < 0.5e-3);
    CHECK(std::abs(r.decentre_y - pose.dy) < 0.5e-3);
    CHECK(std::abs(r.tilt_x - pose.tilt_x) < 1e-6);
    CHECK(std::abs(r.tilt_y - pose.tilt_y) < 1e-6);
    CHECK(std::abs(r.clocking - pose.clocking) < 0.01 * kDeg);
    CHECK(std::abs(r.piston - pose.piston) < 1e-5);
    // The fitted error equals the known one to ≤ 2 nm RMS over the aperture.
    const Zernike fitted(0, 0, {}, r.normalization_radius, r.zernike);
    double sq = 0;
    long n = 0;
    for (double x = -3.95; x <= 3.95; x += 0.05)
      for (double y = -3.95; y <= 3.95; y += 0.05) {
        if (std::hypot(x, y) > 3.95) continue;
        const double d = fitted.sag(x, y) - error.sag(x, y);
        sq += d * d;
        ++n;
      }
    const double rms = std::sqrt(sq / static_cast<double>(n));
    MESSAGE("fitted error against the known: " << rms * 1e6 << " nm RMS");
    CHECK(rms < 2e-6);
    // What the fit leaves is the noise (1 nm RMS).
    CHECK(r.fit_rms == doctest::Approx(1e-6).epsilon(0.2).scale(0));
  }

  TEST_CASE("a bump no Zernike term holds: the B-spline after them takes it, and the pose stays") {
    // The compound eye with astigmatism and trefoil and a Gaussian bump of 0.2 µm (σ 0.6 mm)
    // at (1.5, −1): misregistered, 1 nm noise, 5 % dropouts.
    const auto design = compound_eye();
    const Zernike zernike(0, 0, {}, 4.0, known_error());
    struct Bumped final : Surface {
      const Zernike& e;
      explicit Bumped(const Zernike& z) : e(z) {}
      const char* type() const override { return "bumped"; }
      // A part's form error is defined less its piston and tilt (those are the mounting's,
      // and the pose takes them): the bump less its least-squares plane over the disk.
      static double raw(double x, double y) {
        return 0.2e-3 * std::exp(-((x - 1.5) * (x - 1.5) + (y + 1) * (y + 1)) / (2 * 0.36));
      }
      static const Eigen::Vector3d& plane() {
        static const Eigen::Vector3d abc = [] {
          Eigen::Matrix3d n = Eigen::Matrix3d::Zero();
          Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
          for (double x = -3.99; x <= 4; x += 0.02)
            for (double y = -3.99; y <= 4; y += 0.02) {
              if (std::hypot(x, y) > 4) continue;
              const Eigen::Vector3d f(1, x, y);
              n += f * f.transpose();
              rhs += f * raw(x, y);
            }
          return Eigen::Vector3d(n.ldlt().solve(rhs));
        }();
        return abc;
      }
      static double bump(double x, double y) {
        return raw(x, y) - plane().dot(Eigen::Vector3d(1, x, y));
      }
      void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
        e.sag_gradient(x, y, z, zx, zy);
        z += bump(x, y);
      }
      HeightDerivatives height_derivatives(double x, double y) const override {
        HeightDerivatives h = e.height_derivatives(x, y);
        h.z += bump(x, y);
        return h;
      }
    } error(zernike);
    const Pose pose;
    const Measurement m = measure(*design, zernike, pose, 0.02, 0, 0);
    // measure() adds the Zernike part; the bump is added here, at the design point each
    // measured point came from (noise and dropouts as in the first case, made here).
    Measurement bumped;
    std::mt19937 random(5);
    std::normal_distribution<double> gauss(0, 1e-6);
    std::uniform_real_distribution<double> uniform(0, 1);
    const Eigen::Matrix3d r = pose.rotation();
    const Eigen::Vector3d t(pose.dx, pose.dy, pose.piston);
    for (const Eigen::Vector3d& p : m.points) {
      if (uniform(random) < 0.05) {
        ++bumped.invalid;
        continue;
      }
      const Eigen::Vector3d q = r * p + t;
      bumped.points.push_back(r.transpose() * (q + Eigen::Vector3d(0, 0, Bumped::bump(q.x(), q.y()) + gauss(random)) - t));
    }
    RegistrationOptions o;
    o.zernike_terms = 21;
    o.normalization_radius = o.outer_radius = 4.0;
    o.bspline_control = 24;
    o.bspline_smoothing = 1e-7;  // the square's corners hold no data: a little smoothing fills them
    const Registration g = register_measurement(*design, bumped, o, "m.xyz");
    REQUIRE(g.bspline);
    CHECK(std::abs(g.decentre_x - pose.dx) < 0.5e-3);
    CHECK(std::abs(g.decentre_y - pose.dy) < 0.5e-3);
    CHECK(std::abs(g.tilt_x - pose.tilt_x) < 1e-6);
    CHECK(std::abs(g.tilt_y - pose.tilt_y) < 1e-6);
    CHECK(std::abs(g.clocking - pose.clocking) < 0.01 * kDeg);
    // Zernike + B-spline against the known error, piston apart (the B-spline's mean is a
    // piston the pose also holds), within 2 nm RMS.
    const Zernike fitted(0, 0, {}, g.normalization_radius, g.zernike);
    std::vector<double> d;
    for (double x = -3.8; x <= 3.8; x += 0.05)
      for (double y = -3.8; y <= 3.8; y += 0.05) {
        if (std::hypot(x, y) > 3.8) continue;
        // The B-spline spans [−1.5 R_n, 1.5 R_n]² (kBsplineReach): x and y affine in u, v.
        const double b = g.bspline->point((x + 6) / 12, (y + 6) / 12).z();
        CHECK(bspline_height(*g.bspline, g.normalization_radius, x, y) == b);
        d.push_back(fitted.sag(x, y) + b - error.sag(x, y));
      }
    // The corrected design is evaluated past the aperture (the nose overhangs its edge, a
    // tilted base normal lands beyond it): the B-spline has a value to 1.5 R_n, with x and y
    // those of its square's corners, and the same knot spacing as 24 per side over 2 R_n.
    CHECK(g.bspline_control == 24);
    CHECK(g.bspline->count_u() == 3 + 32);
    CHECK(g.bspline->point(0, 0).x() == doctest::Approx(-6.0).epsilon(1e-12));
    CHECK(g.bspline->point(1, 1).y() == doctest::Approx(6.0).epsilon(1e-12));
    for (double t = 0; t < 2 * M_PI; t += 0.1)
      CHECK(std::isfinite(bspline_height(*g.bspline, 4.0, 5.9 * std::cos(t), 5.9 * std::sin(t))));
    double mean = 0, sq = 0;
    for (const double v : d) mean += v;
    mean /= static_cast<double>(d.size());
    for (const double v : d) sq += (v - mean) * (v - mean);
    const double rms = std::sqrt(sq / static_cast<double>(d.size()));
    MESSAGE("Zernike + B-spline against the known error with the bump: " << rms * 1e6
            << " nm RMS (piston " << mean * 1e6 << " nm); fit residual " << g.fit_rms * 1e6
            << " nm; outliers " << g.outliers);
    CHECK(rms < 2e-6);
    CHECK(g.outliers < 20);
  }

  TEST_CASE("outliers beyond five robust sigmas are dropped, and only they") {
    const auto design = compound_eye();
    const Zernike error(0, 0, {}, 4.0, known_error());
    Measurement m = measure(*design, error, Pose{}, 0.05, 1e-6, 0);
    // Spikes of 5 µm on every 97th point.
    long spikes = 0;
    for (std::size_t i = 0; i < m.points.size(); i += 97, ++spikes) m.points[i].z() += 5e-3;
    RegistrationOptions o;
    o.zernike_terms = 21;
    o.normalization_radius = o.outer_radius = 4.0;
    const Registration r = register_measurement(*design, m, o, "m.xyz");
    CHECK(r.outliers == spikes);
    CHECK(r.fit_rms < 1.5e-6);
  }

  TEST_CASE("points that cannot tell the Zernike terms apart are an error at their file") {
    // On a ring every term is A cos mθ + B sin mθ, and the terms of one m differ only by
    // their radial factor, a constant there: Z4 (defocus) and Z11 (spherical) are both
    // constant on it, Z5 and Z13 both ∝ sin 2θ. A thousand copies of one point, or a line
    // through the axis (every sin mθ term 0 on it), leave as little. The fit would follow
    // any combination of them into the rest of the aperture (1000 copies of one point had
    // tilted the corrected design 85°).
    const auto design = compound_eye();
    RegistrationOptions o;
    o.normalization_radius = o.outer_radius = 4.0;
    o.zernike_terms = 15;
    Measurement ring, copies, line;
    for (int i = 0; i < 1000; ++i) {
      const double t = 2 * std::numbers::pi * i / 1000;
      ring.points.emplace_back(3 * std::cos(t), 3 * std::sin(t), 0.0);
      copies.points.emplace_back(0.5, 0.5, 0.0);
      line.points.emplace_back(-3.9 + 7.8 * i / 999, 0.0, 0.0);
    }
    for (const Measurement* m : {&ring, &copies, &line})
      CHECK_THROWS_WITH_AS(register_measurement(*design, *m, o, "m.xyz"),
                           doctest::Contains("m.xyz: the 1000 valid points inside the aperture "
                                             "cannot tell Zernike term"),
                           InputError);
    // The same ring with terms 4 … 8 (piston and tilt are the pose's): each of another
    // angular order and side (m = 0, ±2, ±1), so the ring tells them apart.
    o.zernike_terms = 8;
    CHECK_NOTHROW(register_measurement(*design, ring, o, "m.xyz"));
  }

  TEST_CASE("a measurement outside the aperture, or running away, is an error at its file") {
    const auto design = compound_eye();
    Measurement far;
    for (int i = 0; i < 500; ++i) far.points.emplace_back(50.0 + i * 0.01, 50.0, 0.0);
    RegistrationOptions o;
    o.normalization_radius = o.outer_radius = 4.0;
    CHECK_THROWS_WITH_AS(register_measurement(*design, far, o, "far.xyz"),
                         doctest::Contains("far.xyz: 0 valid points fall inside the aperture"),
                         InputError);
    // Heights of 1e300 mm (a file in other units, or garbage): the squares overflow, and the
    // first step taken from them would land every point outside the aperture. Before, the
    // outliers' median was then read from no points at all (a segmentation fault).
    Measurement huge;
    for (double x = -3.0; x <= 3.0; x += 0.25)
      for (double y = -3.0; y <= 3.0; y += 0.25) huge.points.emplace_back(x, y, 1e300);
    CHECK_THROWS_WITH_AS(register_measurement(*design, huge, o, "huge.xyz"),
                         doctest::Contains("huge.xyz: the measured heights are too large"),
                         InputError);
  }
}
