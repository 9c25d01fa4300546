#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "freeturn/verify/form_error.hpp"

using namespace freeturn;

namespace {

// A residual grid made of a known figure and known cusps: the cusps of a nose of radius R
// at pitch f, the circular arc d ↦ R − √(R² − d²) with d the distance to the nearest
// contact radius (contacts at k·f), plus a figure A·cos 2φ, constant along each column.
struct Synthetic {
  double f = 0.02, R = 0.5, A = 80e-6, inner = 0.0, step = 0.005;  // mm
  int rings = 400, columns = 72;

  double cusp(double rho) const {
    const double d = std::abs(std::remainder(rho, f));
    return R - std::sqrt(R * R - d * d);
  }
  double figure(int j) const { return A * std::cos(2 * 2 * std::numbers::pi * j / columns); }

  SimulationResult grid() const {
    SimulationResult r;
    r.rings = rings;
    r.columns = columns;
    r.radial_step = step;
    for (int i = 0; i < rings; ++i)
      for (int j = 0; j < columns; ++j) r.residual.push_back(cusp(inner + i * step) + figure(j));
    return r;
  }
};

}  // namespace

TEST_SUITE("verify") {
  TEST_CASE("the figure is the residual's mean over one pitch, the finish the cusps it removed") {
    const Synthetic s;
    const SimulationResult r = s.grid();
    const double outer = s.inner + (s.rings - 1) * s.step, margin = 2 * s.f;
    const FormErrorSplit e = split_figure_finish(r, s.inner, outer, margin, s.f);
    CHECK(e.window == 4);  // 0.02 / 0.005
    CHECK(e.resolved);
    // The cusp's four phases, 0, f/4, f/2, 3f/4, have the same mean in every window: the
    // piston, which is removed from the figure. cos 2φ over 72 columns averages to 0.
    const double d = s.f / 4;
    const double phases[4] = {s.cusp(0), s.cusp(d), s.cusp(2 * d), s.cusp(3 * d)};
    const double piston = (phases[0] + phases[1] + phases[2] + phases[3]) / 4;
    CHECK(e.piston == doctest::Approx(piston).epsilon(1e-9));
    // The figure is A cos 2φ: PV 2A, RMS A/√2.
    CHECK(e.figure_pv == doctest::Approx(2 * s.A).epsilon(1e-6));
    CHECK(e.figure_rms == doctest::Approx(s.A / std::sqrt(2.0)).epsilon(1e-6));
    for (int i = 10; i < s.rings - 10; i += 37)
      for (int j = 0; j < s.columns; j += 5)
        CHECK(e.figure[static_cast<std::size_t>(i * s.columns + j)] ==
              doctest::Approx(s.figure(j)).epsilon(1e-5).scale(1e-6));
    // The finish is the cusp less its mean: PV the cusp's own sampled PV, R − √(R² − (f/2)²)
    // at the crest, 0 at the contact.
    const double crest = s.R - std::sqrt(s.R * s.R - s.f * s.f / 4);
    CHECK(e.finish_pv == doctest::Approx(crest).epsilon(1e-9));
    double sq = 0;
    for (const double p : phases) sq += (p - piston) * (p - piston);
    CHECK(e.finish_rms == doctest::Approx(std::sqrt(sq / 4)).epsilon(1e-9));
    for (const double band : e.finish_pv_by_band) CHECK(band == doctest::Approx(crest).epsilon(1e-9));
  }

  TEST_CASE("a grid coarser than a third of the pitch is flagged as not resolving the cusps") {
    Synthetic s;
    s.step = 0.01;  // two cells a pitch
    s.rings = 200;
    const SimulationResult r = s.grid();
    const FormErrorSplit e = split_figure_finish(r, 0, (s.rings - 1) * s.step, 2 * s.f, s.f);
    CHECK(e.window == 2);
    CHECK_FALSE(e.resolved);
  }

  TEST_CASE("cells never cut stay out of the figure and of the figures") {
    const Synthetic s;
    SimulationResult r = s.grid();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // A spike where nothing was cut would move every figure if it were counted.
    for (int j = 0; j < s.columns; ++j) r.residual[static_cast<std::size_t>(200 * s.columns + j)] = nan;
    const FormErrorSplit e =
        split_figure_finish(r, s.inner, s.inner + (s.rings - 1) * s.step, 2 * s.f, s.f);
    CHECK(std::isnan(e.figure[static_cast<std::size_t>(200 * s.columns)]));
    // The windows beside the gap miss one phase of the cusp: their mean moves by at most
    // the crest over the three left, and nothing else does.
    const double crest = s.R - std::sqrt(s.R * s.R - s.f * s.f / 4);
    CHECK(std::isfinite(e.figure_pv));
    CHECK(e.figure_pv >= 2 * s.A * (1 - 1e-6));
    CHECK(e.figure_pv <= 2 * s.A + 2 * crest / 3);
  }
}
