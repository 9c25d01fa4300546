#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "freeturn/core/dense_qp.hpp"

using namespace freeturn;

namespace {

// The QP's answer by brute force: every subset of rows taken as equalities, its KKT
// system solved directly; the best point that is feasible with multipliers ≥ 0.
Eigen::VectorXd brute_force(const Eigen::MatrixXd& G, const Eigen::VectorXd& a,
                            const Eigen::MatrixXd& C, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(G.rows()), m = static_cast<int>(C.rows());
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd answer;
  for (int mask = 0; mask < (1 << m); ++mask) {
    std::vector<int> rows;
    for (int i = 0; i < m; ++i)
      if (mask & (1 << i)) rows.push_back(i);
    const int q = static_cast<int>(rows.size());
    if (q > n) continue;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + q, n + q);
    Eigen::VectorXd rhs(n + q);
    K.topLeftCorner(n, n) = G;
    rhs.head(n) = -a;
    for (int j = 0; j < q; ++j) {
      K.block(0, n + j, n, 1) = -C.row(rows[static_cast<std::size_t>(j)]).transpose();
      K.block(n + j, 0, 1, n) = C.row(rows[static_cast<std::size_t>(j)]);
      rhs(n + j) = b(rows[static_cast<std::size_t>(j)]);
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (lu.rank() < n + q) continue;
    const Eigen::VectorXd s = lu.solve(rhs);
    const Eigen::VectorXd x = s.head(n);
    if ((s.tail(q).array() < -1e-12).any()) continue;
    if (((C * x - b).array() < -1e-10).any()) continue;
    const double f = 0.5 * x.dot(G * x) + a.dot(x);
    if (f < best) best = f, answer = x;
  }
  return answer;
}

}  // namespace

TEST_SUITE("core") {
  TEST_CASE("dense QP: one active row, by hand") {
    // min ½|x|² − x₁ − x₂ subject to x₁ + x₂ ≤ 1: x = (½, ½), multiplier ½.
    const Eigen::MatrixXd G = Eigen::MatrixXd::Identity(2, 2);
    const Eigen::VectorXd a = Eigen::Vector2d(-1, -1);
    Eigen::MatrixXd C(1, 2);
    C << -1, -1;
    const Eigen::VectorXd b = Eigen::VectorXd::Constant(1, -1);
    const DenseQpResult r = solve_dense_qp(G, a, C, b);
    REQUIRE(r.status == Status::kOk);
    CHECK(r.x(0) == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(r.x(1) == doctest::Approx(0.5).epsilon(1e-14));
    REQUIRE(r.active.size() == 1);
    CHECK(r.multipliers[0] == doctest::Approx(0.5).epsilon(1e-14));
    CHECK(r.objective == doctest::Approx(0.25 - 1).epsilon(1e-14));
  }

  TEST_CASE("dense QP: random problems agree with brute-force KKT enumeration") {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 40; ++trial) {
      const int n = 2 + trial % 3, m = 4 + trial % 5;
      Eigen::MatrixXd M(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) M(i, j) = normal(rng);
      const Eigen::MatrixXd G = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
      Eigen::VectorXd a(n), b(m);
      Eigen::MatrixXd C(m, n);
      for (int i = 0; i < n; ++i) a(i) = 3 * normal(rng);
      for (int k = 0; k < m; ++k) {
        for (int i = 0; i < n; ++i) C(k, i) = normal(rng);
        b(k) = -std::abs(normal(rng)) - 0.1;  // x = 0 is strictly feasible: the QP has an answer
      }
      const DenseQpResult r = solve_dense_qp(G, a, C, b);
      REQUIRE(r.status == Status::kOk);
      const Eigen::VectorXd expected = brute_force(G, a, C, b);
      REQUIRE(expected.size() == n);
      CAPTURE(trial);
      CHECK((r.x - expected).norm() < 1e-9);
      for (double u : r.multipliers) CHECK(u >= -1e-12);
    }
  }

  TEST_CASE("dense QP: a thousand rows, two active (the nearest point of a polygon)") {
    // The regular 1000-gon around the unit circle with a vertex at (1, 0): the point of
    // it nearest (2, 0) is that vertex, where two edges meet.
    const int sides = 1000;
    Eigen::MatrixXd C(sides, 2);
    Eigen::VectorXd b(sides);
    for (int k = 0; k < sides; ++k) {
      const double phi = (2 * k + 1) * std::numbers::pi / sides;  // the edge normals
      C(k, 0) = -std::cos(phi), C(k, 1) = -std::sin(phi);
      b(k) = -std::cos(std::numbers::pi / sides);
    }
    const DenseQpResult r = solve_dense_qp(Eigen::MatrixXd::Identity(2, 2),
                                           Eigen::Vector2d(-2, 0), C, b);
    REQUIRE(r.status == Status::kOk);
    CHECK(r.x(0) == doctest::Approx(1).epsilon(1e-12));
    CHECK(std::abs(r.x(1)) < 1e-12);
    CHECK(r.active.size() == 2);
  }
}
