#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "freeturn/nurbs/curve.hpp"
#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/minimax_base_fit.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/transformed_surface.hpp"
#include "path/fixtures.hpp"

using namespace freeturn;

namespace {

LensletArrayOptions eye_options() { return test::compound_eye_options(6.5); }

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("base surface: a plane's arc length is ρ; a cubic generating curve's is its integral") {
    const BaseSurface plane = BaseSurface::plane(10);
    CHECK(plane.arc_length(3.25) == 3.25);
    CHECK(plane.at_arc_length(7.5).rho == 7.5);
    // H = ρ³/100 on [0, 4] as one cubic Bézier span: coefficients from the Bernstein form
    // (ρ = 4t, H = 0.64 t³): (0, 0, 0, 0.64).
    const BaseSurface cubic(3, {0, 0, 0, 0, 4, 4, 4, 4}, {0, 0, 0, 0.64});
    const auto b = cubic.at_radius(3.0);
    CHECK(b.h == doctest::Approx(0.27).epsilon(1e-14));
    CHECK(b.slope == doctest::Approx(0.27).epsilon(1e-14));
    CHECK(b.curvature == doctest::Approx(0.18).epsilon(1e-14));
    // s(3) = ∫₀³ √(1 + (0.03ρ²)²) dρ, by Simpson's rule on 2000 intervals.
    double s = 0;
    for (int i = 0; i <= 2000; ++i) {
      const double rho = 3.0 * i / 2000, d = 0.03 * rho * rho;
      s += std::sqrt(1 + d * d) * (i == 0 || i == 2000 ? 1 : (i % 2 ? 4 : 2));
    }
    s *= 3.0 / 2000 / 3;
    CHECK(cubic.arc_length(3.0) == doctest::Approx(s).epsilon(1e-12));
    CHECK(cubic.at_arc_length(s).rho == doctest::Approx(3.0).epsilon(1e-12));
  }

  TEST_CASE("base surface: H, H' and H'' agree with the rational curve through the same net") {
    // The base evaluates its scalar spline directly (A2.2 and the derivative splines); the
    // NURBS kernel's curve (A3.2, A2.3, the quotient rule) through the Greville abscissae
    // and the same coefficients is the second method. Degrees 1 to 5, a double knot inside
    // (single for degree 1).
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> coefficient(-0.3, 0.3);
    for (int p = 1; p <= 5; ++p) {
      CAPTURE(p);
      std::vector<double> knots(static_cast<std::size_t>(p) + 1, 0.0);
      for (const double k : {0.7, 1.9, 1.9, 2.6, 3.1})
        if (!(p == 1 && k == 1.9 && knots.back() == 1.9)) knots.push_back(k);  // C⁰ at most
      knots.insert(knots.end(), static_cast<std::size_t>(p) + 1, 4.0);
      const std::size_t n = knots.size() - static_cast<std::size_t>(p) - 1;
      std::vector<double> c(n);
      for (double& v : c) v = coefficient(rng);
      std::vector<nurbs::Vector3d> net;
      for (std::size_t i = 0; i < n; ++i) {
        double g = 0;
        for (int j = 1; j <= p; ++j) g += knots[i + static_cast<std::size_t>(j)];
        net.emplace_back(g / p, c[i], 0.0);
      }
      const nurbs::NurbsCurve curve(p, knots, net);
      const BaseSurface base(p, knots, c);
      for (int i = 0; i <= 400; ++i) {
        const double rho = 4.0 * i / 400;
        CAPTURE(rho);
        const BasePoint b = base.at_radius(rho);
        const nurbs::CurveDerivatives d = curve.evaluate(rho, 2);
        CHECK(std::abs(d.point.x() - rho) <= 1e-14);  // the Greville net reproduces ρ
        CHECK(std::abs(b.h - d.point.y()) <= 1e-14);
        CHECK(std::abs(b.slope - d.d1.y()) <= 1e-13);
        if (p >= 2 && rho != 1.9) CHECK(std::abs(b.curvature - d.d2.y()) <= 1e-12);
        if (p < 2) CHECK(b.curvature == 0);
      }
    }
  }

  TEST_CASE("least-squares base: exact for a profile in the spline space, with H'(0) = 0") {
    // z = 0.01ρ² + 0.002ρ³ is a cubic in ρ with zero slope on the axis.
    struct Profile final : Surface {
      const char* type() const override { return "test"; }
      void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
        const double r = std::hypot(x, y);
        z = 0.01 * r * r + 0.002 * r * r * r;
        zx = (0.02 + 0.006 * r) * x;
        zy = (0.02 + 0.006 * r) * y;
      }
      HeightDerivatives height_derivatives(double x, double y) const override {
        HeightDerivatives h;
        sag_gradient(x, y, h.z, h.zx, h.zy);
        return h;
      }
    } profile;
    const auto samples = sample_aperture(profile, 0, 8.0, 24, 16);
    const BaseSurface base = fit_base_least_squares(samples);
    for (double rho : {0.0, 1.3, 4.0, 7.9}) {
      CHECK(base.at_radius(rho).h == doctest::Approx(0.01 * rho * rho + 0.002 * rho * rho * rho)
                                         .epsilon(1e-9)
                                         .scale(1));
    }
    CHECK(base.at_radius(0).slope == 0.0);
    CHECK(measure_quasi_revolution(samples, base).max_angle < 1e-8);
  }

  TEST_CASE("compound eye: the fitted base has far smaller α than a plane; minimax lowers it") {
    const LensletArray eye(eye_options());
    const auto samples = sample_aperture(eye, 0, 6.0, 60, 120);
    const QuasiRevolution plane = measure_quasi_revolution(samples, BaseSurface::plane(6.0));
    BaseFitOptions fo;
    fo.spans = 6;
    const BaseSurface lsq = fit_base_least_squares(samples, fo);
    const QuasiRevolution fitted = measure_quasi_revolution(samples, lsq);
    // The base sphere's slope at r = 6 is asin(6/20) = 17.5°, the lenslets' rim 5.2°.
    const double deg = std::numbers::pi / 180;
    CHECK(plane.max_angle > 20 * deg);
    CHECK(fitted.max_angle < 0.4 * plane.max_angle);
    const MinimaxBaseResult minimax = fit_base_minimax(samples, lsq);
    CHECK(minimax.status == Status::kOk);
    CHECK(minimax.start_max_angle == doctest::Approx(fitted.max_angle).epsilon(1e-9));
    // The optimiser's α_max is the measured one of its base.
    CHECK(measure_quasi_revolution(samples, minimax.base).max_angle ==
          doctest::Approx(minimax.max_angle).epsilon(1e-9));
    MESSAGE("α_max: plane " << plane.max_angle / deg << "°, least squares " << fitted.max_angle / deg
                            << "°, minimax " << minimax.max_angle / deg << "° (" << minimax.iterations
                            << " iterations)");
    CHECK(minimax.max_angle < fitted.max_angle - 0.01 * deg);
    // A minimum, seen without the optimiser: no small random change of the free
    // coefficients (c_0 = c_1 keep H'(0) = 0) lowers the largest angle.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    const std::vector<double>& c = minimax.base.coefficients();
    for (double size : {1e-3, 1e-4, 1e-5}) {
      for (int trial = 0; trial < 40; ++trial) {
        std::vector<double> moved = c;
        for (std::size_t i = 2; i < moved.size(); ++i) moved[i] += size * unit(rng);
        const BaseSurface other(minimax.base.degree(), minimax.base.knots(), moved);
        CHECK(measure_quasi_revolution(samples, other).max_angle >= minimax.max_angle - 1e-12);
      }
    }
  }

  TEST_CASE("axis search recovers a tilted, decentred paraboloid's axis exactly") {
    // A paraboloid (R 10 mm) tilted 1.5° about y and decentred 0.3 mm in x: a surface of
    // revolution about R e_z through R·(−o), o = (0.3, 0, z(0.3, 0)) (its parent vertex).
    const Eigen::Matrix3d rotation = TransformedSurface::rotation_from_tilts(0, 1.5 * std::numbers::pi / 180);
    const TransformedSurface part(std::make_unique<EvenAsphere>(0.1, -1.0), 0.3, 0, rotation);
    const auto samples = sample_aperture(part, 0, 6.0, 24, 48);
    BaseFitOptions fo;
    fo.rho_max = 8.0;
    MinimaxBaseOptions mo;
    mo.search_axis = true;
    const MinimaxBaseResult r = fit_base_minimax(samples, fit_base_least_squares(samples, fo), mo);
    CHECK(r.status == Status::kOk);
    const Eigen::Vector3d axis = rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d through = rotation * -Eigen::Vector3d(0.3, 0, 0.3 * 0.3 / 20);
    CHECK(r.axis.direction().cross(axis).norm() < 1e-9);
    const Eigen::Vector3d d = through - r.axis.point();
    CHECK((d - d.dot(axis) * axis).norm() < 1e-8);
    CHECK(r.max_angle < 1e-9);  // the paraboloid is in the cubic spline space
  }

  TEST_CASE("minimax axis search on a tilted compound eye: as good as the eye's own axis") {
    const double tilt = 1.0 * std::numbers::pi / 180;
    const TransformedSurface eye(std::make_unique<LensletArray>(eye_options()), 0, 0,
                                 TransformedSurface::rotation_from_tilts(tilt, 0));
    const auto samples = sample_aperture(eye, 0, 5.0, 40, 96);
    BaseFitOptions fo;
    fo.spans = 6;
    fo.rho_max = 6.5;  // room for the axis to move
    MinimaxBaseOptions mo;
    mo.search_axis = true;
    mo.max_shift = 2.0;
    const MinimaxBaseResult r = fit_base_minimax(samples, fit_base_least_squares(samples, fo), mo);
    // The same sampling of the untilted eye, with its own (z) axis.
    const LensletArray upright(eye_options());
    const auto upright_samples = sample_aperture(upright, 0, 5.0, 40, 96);
    const MinimaxBaseResult own = fit_base_minimax(upright_samples, fit_base_least_squares(upright_samples, fo));
    const double deg = std::numbers::pi / 180;
    const Eigen::Vector3d axis =
        TransformedSurface::rotation_from_tilts(tilt, 0) * Eigen::Vector3d::UnitZ();
    const double angle = std::acos(std::min(1.0, r.axis.direction().dot(axis)));
    MESSAGE("axis found " << angle / deg << "° from the eye's; α_max " << r.max_angle / deg
                          << "° (least squares " << r.least_squares_max_angle / deg
                          << "°, z axis " << r.start_max_angle / deg << "°, eye's own axis "
                          << own.max_angle / deg << "°)");
    CHECK(r.max_angle < r.start_max_angle - 1 * deg);
    CHECK(r.max_angle <= own.max_angle + 0.02 * deg);
    // The lenslets decide the axis only weakly (the minimax is flat along it), but it is
    // near the eye's and passes through its base sphere's centre R·(0, 0, 20).
    CHECK(angle < 0.25 * deg);
    const Eigen::Vector3d d = 20.0 * axis - r.axis.point();
    CHECK((d - d.dot(r.axis.direction()) * r.axis.direction()).norm() < 0.01);
  }
}

#include "freeturn/core/error.hpp"
#include "freeturn/path/base_plan.hpp"

TEST_SUITE("path") {
  TEST_CASE("base plan: a searched axis re-expresses the design about it; α limits refuse or warn") {
    const Eigen::Matrix3d rotation = TransformedSurface::rotation_from_tilts(0.02, -0.01);
    const TransformedSurface part(std::make_unique<EvenAsphere>(0.1, -1.0), 0.2, -0.1, rotation);
    BasePlanOptions o;
    o.kind = BaseKind::kMinimax;
    o.search_axis = true;
    o.radial_samples = 16;
    o.angular_samples = 32;
    const BasePlan plan = plan_base_surface(part, 0, 5.0, o);
    REQUIRE(plan.design_about_axis != nullptr);
    const Surface& cut = plan.design_to_cut(part);
    // About the found axis the paraboloid is a paraboloid again: z = r²/20, vertex at 0.
    for (double r : {0.0, 1.0, 4.5})
      for (double phi : {0.0, 2.0, 4.0})
        CHECK(cut.sag(r * std::cos(phi), r * std::sin(phi)) ==
              doctest::Approx(r * r / 20).epsilon(1e-9).scale(1));
    CHECK(plan.quasi_revolution.max_angle < 1e-8);
    // What the report tells the shop to mount the part by: the axis is the paraboloid's,
    // tilted from z by the angle the part was rotated by (acos of R's zz entry, whichever
    // way R is read), and it crosses the design at axis_crossing, a point on both.
    const Eigen::Vector3d t = plan.axis.direction();
    CHECK(std::acos(t.z()) == doctest::Approx(std::acos(rotation(2, 2))).epsilon(1e-7));
    const Eigen::Vector3d c = plan.axis_crossing;
    CHECK(part.sag(c.x(), c.y()) == doctest::Approx(c.z()).epsilon(1e-9).scale(1));
    const Eigen::Vector3d off_axis = (c - plan.axis.point()) - (c - plan.axis.point()).dot(t) * t;
    CHECK(off_axis.norm() < 1e-8);

    const LensletArray eye(eye_options());
    BasePlanOptions limited;
    limited.angle_limit = 3 * std::numbers::pi / 180;
    limited.radial_samples = 30;
    limited.angular_samples = 60;
    CHECK_THROWS_WITH_AS(plan_base_surface(eye, 0, 6.0, limited),
                         doctest::Contains("the design is not of quasi-revolution for its base: α "
                                           "reaches 7."),
                         freeturn::InputError);
    limited.refuse_above_limit = false;
    const BasePlan warned = plan_base_surface(eye, 0, 6.0, limited);
    REQUIRE(warned.warnings.size() == 1);
    CHECK(warned.warnings[0].find("above the limit 3.000000°") != std::string::npos);
    CHECK(warned.design_about_axis == nullptr);
  }
}
