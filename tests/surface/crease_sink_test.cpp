// The crease list a section fills (surface/crease_sink.hpp): the lowest that fit, ascending,
// whatever order they come in, and the count of all of them, against a sorted copy.
#include "freeturn/surface/crease_sink.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "freeturn/surface/lenslet_array.hpp"

using namespace freeturn;

TEST_SUITE("surface") {
  TEST_CASE("crease sink: the lowest that fit, ascending, and the count of all") {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> where(-1.0, 1.0);
    for (const int n : {0, 3, 8, 9, 40}) {
      CAPTURE(n);
      std::vector<double> rho(static_cast<std::size_t>(n));
      for (double& r : rho) r = where(random);
      std::array<double, 8> out;
      CreaseSink sink(out, -0.9, 0.9);
      for (const double r : rho) sink.add(r);
      std::vector<double> inside;
      for (const double r : rho)
        if (r >= -0.9 && r <= 0.9) inside.push_back(r);
      std::sort(inside.begin(), inside.end());
      CHECK(sink.finish() == static_cast<int>(inside.size()));
      for (std::size_t k = 0; k < std::min<std::size_t>(8, inside.size()); ++k)
        CHECK(out[k] == inside[k]);
    }
  }

  TEST_CASE("crease sink: one crease found twice is listed once") {
    std::array<double, 4> out;
    CreaseSink sink(out, 0.0, 1.0, 1e-9);
    for (const double r : {0.5, 0.2, 0.5 + 5e-10, 0.2 - 5e-10, 0.7}) sink.add(r);
    CHECK(sink.finish() == 3);
    CHECK(out[0] == 0.2);
    CHECK(out[1] == 0.5);
    CHECK(out[2] == 0.7);
  }

  TEST_CASE("crease sink: a lenslet array's section told into a short list") {
    // A fine square array (pitch 0.05 mm): the section across 2 mm meets dozens of rims.
    // Told into 12 places, the list is the first 12 of the whole list, and the count the
    // whole list's. Found lenslet by lenslet, the first 12 found had been kept.
    const LensletArray fine({.lens_radius = 0.3,
                             .lens_diameter = 0.045,
                             .pitch = 0.05,
                             .pattern = LensletArrayOptions::Pattern::kSquare,
                             .extent = 1.2});
    for (const double theta : {0.0, 0.3, 2.0}) {
      CAPTURE(theta);
      std::array<double, 512> all;
      const int count = fine.section_creases(RadialLine(theta), -1.0, 1.0, all);
      REQUIRE(count > 24);
      REQUIRE(count <= 512);
      CHECK(std::is_sorted(all.begin(), all.begin() + count));
      std::array<double, 12> some;
      CHECK(fine.section_creases(RadialLine(theta), -1.0, 1.0, some) == count);
      for (std::size_t k = 0; k < some.size(); ++k) CHECK(some[k] == all[k]);
    }
  }
}
