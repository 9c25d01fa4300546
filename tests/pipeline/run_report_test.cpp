#include <doctest/doctest.h>

#include <numbers>

#include "freeturn/pipeline/run_report.hpp"

using namespace freeturn;

TEST_SUITE("pipeline") {
  TEST_CASE("the report's turn samples take a path that starts below θ = 0") {
    // A program read back may start at a negative C (an accumulating C axis, a sign of −1):
    // its first turn is −1, the value turn_ starts at, and the first sample had gone into a
    // turn never opened (a crash in `simulate --program`).
    TurnSamples samples;
    const double step = 2 * std::numbers::pi / TurnSamples::kTurnPoints;
    for (int k = -10; k < 3 * TurnSamples::kTurnPoints; ++k) samples.add((k + 0.5) * step, k, 0);  // mid-step: no floor on a boundary
    // Turns −1, 0, 1 and 2, one sample per step of each: 10, 240, 240 and 240.
    REQUIRE(samples.turns.size() == 4);
    CHECK(samples.turns[0].size() == 10);
    CHECK(samples.turns[1].size() == TurnSamples::kTurnPoints);
    CHECK(samples.turns[3].size() == TurnSamples::kTurnPoints);
    CHECK(samples.turns[0].front().first == -10.0f);
    CHECK(samples.start_x == -10);
  }
}
