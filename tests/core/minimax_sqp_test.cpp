#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "freeturn/core/minimax_sqp.hpp"

using namespace freeturn;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

TEST_SUITE("core") {
  TEST_CASE("minimax SQP: the best uniform quadratic for t³ on [−1, 1] (Chebyshev)") {
    // t³ − p(t) is smallest in the uniform norm for p(t) = ¾t: the error ¼T₃(t), at most
    // ¼, reached at t = ±1, ±½ (on the grid).
    const int samples = 2001;
    const MinimaxFunctions f = [&](const Eigen::VectorXd& c, Eigen::VectorXd& phi, Eigen::MatrixXd& g) {
      phi.resize(2 * samples);
      g.resize(2 * samples, 3);
      for (int j = 0; j < samples; ++j) {
        const double t = -1 + 2.0 * j / (samples - 1);
        const double e = t * t * t - (c(0) + c(1) * t + c(2) * t * t);
        phi(2 * j) = e, phi(2 * j + 1) = -e;
        g.row(2 * j) << -1, -t, -t * t;
        g.row(2 * j + 1) << 1, t, t * t;
      }
    };
    const MinimaxSqpResult r = minimise_max(f, Eigen::Vector3d(0.3, -0.2, 0.1),
                                            Eigen::Vector3d::Constant(-kInf),
                                            Eigen::Vector3d::Constant(kInf));
    CHECK(r.status == Status::kOk);
    CHECK(r.value == doctest::Approx(0.25).epsilon(1e-10));
    CHECK(std::abs(r.x(0)) < 1e-9);
    CHECK(r.x(1) == doctest::Approx(0.75).epsilon(1e-9));
    CHECK(std::abs(r.x(2)) < 1e-9);
  }

  TEST_CASE("minimax SQP: the smallest circle around an acute triangle is its circumcircle") {
    // Vertices (0, 0), (2, 0), (1, 1.5): the circumcentre (1, 5/12), radius² 1 + 25/144.
    const double px[3] = {0, 2, 1}, py[3] = {0, 0, 1.5};
    const MinimaxFunctions f = [&](const Eigen::VectorXd& x, Eigen::VectorXd& phi, Eigen::MatrixXd& g) {
      phi.resize(3);
      g.resize(3, 2);
      for (int k = 0; k < 3; ++k) {
        phi(k) = (x(0) - px[k]) * (x(0) - px[k]) + (x(1) - py[k]) * (x(1) - py[k]);
        g.row(k) << 2 * (x(0) - px[k]), 2 * (x(1) - py[k]);
      }
    };
    const MinimaxSqpResult r = minimise_max(f, Eigen::Vector2d(-3, 4), Eigen::Vector2d::Constant(-kInf),
                                            Eigen::Vector2d::Constant(kInf));
    CHECK(r.status == Status::kOk);
    CHECK(r.x(0) == doctest::Approx(1).epsilon(1e-8));
    CHECK(r.x(1) == doctest::Approx(5.0 / 12).epsilon(1e-8));
    CHECK(r.value == doctest::Approx(1 + 25.0 / 144).epsilon(1e-12));
  }

  TEST_CASE("minimax SQP: a bound that holds the answer") {
    // max(−x, −2x) falls without end; x ≤ 3 stops it at x = 3, F = −3.
    const MinimaxFunctions f = [](const Eigen::VectorXd& x, Eigen::VectorXd& phi, Eigen::MatrixXd& g) {
      phi.resize(2);
      g.resize(2, 1);
      phi << -x(0), -2 * x(0);
      g << -1, -2;
    };
    const MinimaxSqpResult r = minimise_max(f, Eigen::VectorXd::Constant(1, 0.5),
                                            Eigen::VectorXd::Constant(1, -kInf),
                                            Eigen::VectorXd::Constant(1, 3));
    CHECK(r.status == Status::kOk);
    CHECK(r.x(0) == doctest::Approx(3).epsilon(1e-14));
    CHECK(r.value == doctest::Approx(-3).epsilon(1e-14));
  }
}
