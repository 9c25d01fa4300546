// The post-processors' number formatter (plugins/include/freeturn/post_format.hpp): it
// cannot overrun for any double or decimals setting, and what it writes reads back as the
// value rounded to the decimals.
#include "freeturn/post_format.hpp"

#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

using namespace freeturn::post;

TEST_SUITE("plugins") {
  TEST_CASE("the NC number formatter stays in its buffer for every double and decimals setting") {
    const double values[] = {0.0, -0.0, 1.0, -1.0, 0.5, 1e300, -1e300, 1e-300, -1e-300,
                             std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                             std::numeric_limits<double>::min(), 123456789.123456789, 1e20, 1e30, -9.9999999999e25,
                             std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()};
    int written = 0, refused = 0;
    for (const double v : values)
      for (int decimals = -5; decimals <= 400; ++decimals) {
        // A canary past the buffer's end, and sentinel bytes inside it.
        char buffer[kNumberCapacity + 8];
        std::memset(buffer, 0x5A, sizeof buffer);
        const int n = format_fixed(v, decimals, buffer);
        for (int i = kNumberCapacity - 1; i < static_cast<int>(sizeof buffer); ++i)
          REQUIRE(buffer[i] == 0x5A);
        REQUIRE(n >= 0);
        REQUIRE(n < kNumberCapacity);
        if (n == 0) {
          ++refused;
          // Refused exactly when it cannot be written: not finite, decimals out of range,
          // or longer than the room (|v| ≥ 1e30 needs 31 digits before the point).
          const bool fits = std::isfinite(v) && decimals >= 0 && decimals <= kMaxDecimals &&
                            std::abs(v) < 1e30;
          CHECK_FALSE(fits);
          continue;
        }
        ++written;
        const std::string text(buffer, static_cast<std::size_t>(n));
        // Digits, at most one point and a leading minus: nothing else, never "-0".
        for (std::size_t i = 0; i < text.size(); ++i)
          REQUIRE(((text[i] >= '0' && text[i] <= '9') || text[i] == '.' || (i == 0 && text[i] == '-')));
        const double back = std::strtod(text.c_str(), nullptr);
        if (back == 0) CHECK(text.front() != '-');
        // Within half a unit of the last place of the value (a correctly rounded fixed form).
        CHECK(std::abs(back - v) <= 0.5 * std::pow(10.0, -decimals) * (1 + 1e-12) + std::abs(v) * 1e-15);
      }
    CHECK(written > 100);
    CHECK(refused > 100);
  }

  TEST_CASE("the NC number formatter writes what std::to_chars writes, ties included") {
    // The formatter's fast path (an integer and an FMA) against to_chars, the exact
    // reference: random values of every size a word takes, and values at and next to
    // decimal ties (k + 0.5 units of the last place, and the doubles either side).
    std::uint64_t state = 20261202;
    const auto next = [&] {  // SplitMix64
      state += 0x9E3779B97F4A7C15ull;
      std::uint64_t z = state;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      return z ^ (z >> 31);
    };
    long compared = 0;
    for (int n = 0; n < 300000; ++n) {
      const int decimals = static_cast<int>(next() % (kMaxDecimals + 1));
      const double unit = std::pow(10.0, -decimals);
      const double magnitude = std::pow(10.0, static_cast<double>(next() % 18) - 6.0);
      double v = (static_cast<double>(next() >> 11) / 9007199254740992.0 - 0.5) * magnitude;
      if (n % 3 == 1) v = (std::round(v / unit) + 0.5) * unit;  // a tie, as near as a double gets
      if (n % 3 == 2) v = std::nextafter((std::round(v / unit) + 0.5) * unit, n % 2 ? 1e300 : -1e300);
      char fast[kNumberCapacity], slow[kNumberCapacity];
      const int got = format_fixed(v, decimals, fast);
      const auto [end, error] = std::to_chars(slow, slow + kNumberCapacity - 1, v, std::chars_format::fixed, decimals);
      REQUIRE(error == std::errc());
      std::string expected(slow, end);
      if (expected.find_first_not_of("-0.") == std::string::npos && expected.front() == '-') expected.erase(0, 1);
      REQUIRE_MESSAGE(std::string(fast, static_cast<std::size_t>(got)) == expected, v, " at ", decimals);
      ++compared;
    }
    CHECK(compared == 300000);
  }

  TEST_CASE("C wrapped below 360: the rounded angle's text, 360 written as 0") {
    // The reference is the definition: round to the decimals in binary, wrap, print.
    std::uint64_t state = 7;
    const auto next = [&] {
      state += 0x9E3779B97F4A7C15ull;
      std::uint64_t z = state;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      return z ^ (z >> 31);
    };
    for (int k = 0; k < 200000; ++k) {
      const int decimals = static_cast<int>(next() % (kMaxDecimals + 1));
      const double scale = std::pow(10.0, decimals);
      double v = static_cast<double>(next() >> 11) / 9007199254740992.0 * 370.0 - 5.0;
      if (k % 4 == 1) v = 360.0 - static_cast<double>(next() % 3) / scale * 0.5;  // at the wrap
      if (k % 4 == 2) v = -static_cast<double>(next() % 3) / scale * 0.5;         // at zero
      char got[kNumberCapacity], expected[kNumberCapacity];
      const int n = format_wrapped_degrees(v, decimals, got);
      double rounded = std::nearbyint(v * scale) / scale;
      if (rounded >= 360.0) rounded -= 360.0;
      const int m = format_fixed(rounded, decimals, expected);
      REQUIRE_MESSAGE(std::string(got, static_cast<std::size_t>(n)) ==
                          std::string(expected, static_cast<std::size_t>(m)),
                      v, " at ", decimals);
    }
    char text[kNumberCapacity];
    CHECK(std::string(text, static_cast<std::size_t>(format_wrapped_degrees(359.99996, 4, text))) == "0.0000");
    CHECK(std::string(text, static_cast<std::size_t>(format_wrapped_degrees(-0.00004, 4, text))) == "0.0000");
  }

  TEST_CASE("a word that cannot be written throws instead of writing half of it") {
    std::string line = "G93 ";
    CHECK_THROWS_AS(append_word(line, 'F', 1e300, 6), std::range_error);
    CHECK_THROWS_AS(append_number(line, std::nan(""), 3), std::range_error);
    CHECK_THROWS_AS(append_word(line, 'X', 1.0, 100), std::range_error);
    CHECK(line == "G93 ");  // nothing appended
    // 0.0012345 is stored as 0.00123449999…: correctly rounded, that is 0.001234.
    append_word(line, 'F', 0.0012345, 6);
    CHECK(line == "G93 F0.001234");
    append_word(line, 'C', 359.9999996, 6, true);
    CHECK(line == "G93 F0.001234C0.000000");
  }
}
