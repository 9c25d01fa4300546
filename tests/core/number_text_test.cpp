#include <doctest/doctest.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <random>
#include <string>

#include "freeturn/core/number_text.hpp"

using namespace freeturn;

namespace {

// The reference: std::from_chars over the whole text, finite.
bool reference(const std::string& text, double& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

}  // namespace

TEST_SUITE("core") {
  TEST_CASE("parse_plain_decimal reads every NC-style number to the bit from_chars reads") {
    std::mt19937_64 random(20261202);
    const char alphabet[] = "0123456789";
    long compared = 0;
    for (int n = 0; n < 400000; ++n) {
      // Numbers as posts write them (a sign, up to 22 digits, a point anywhere or none),
      // half of them ties and near-ties of the fast path's rounding (long tails of 9s and 5s).
      std::string text = random() % 3 == 0 ? "-" : "";
      const int length = 1 + static_cast<int>(random() % 22);
      const int point = static_cast<int>(random() % (length + 2)) - 1;
      for (int k = 0; k < length; ++k) {
        if (k == point) text += '.';
        const std::uint64_t pick = random() % 10;
        text += n % 2 == 0 ? alphabet[pick] : (pick < 5 ? '9' : pick < 8 ? '5' : alphabet[pick]);
      }
      double expected = 0, got = 0;
      const bool expected_ok = reference(text, expected);
      const bool got_ok = parse_plain_decimal(text, got);
      REQUIRE_MESSAGE(expected_ok == got_ok, text);
      if (expected_ok) {
        REQUIRE_MESSAGE(std::bit_cast<std::uint64_t>(expected) == std::bit_cast<std::uint64_t>(got),
                        text);
        ++compared;
      }
    }
    CHECK(compared > 390000);
  }

  TEST_CASE("parse_plain_decimal refuses what is not a plain decimal") {
    double v = 0;
    CHECK(parse_plain_decimal("12.500", v));
    CHECK(v == 12.5);
    CHECK(parse_plain_decimal("-0.000001", v));
    CHECK(v == -1e-6);
    CHECK(parse_plain_decimal(".5", v));
    CHECK(v == 0.5);
    CHECK(parse_plain_decimal("5.", v));
    CHECK(v == 5);
    for (const char* bad : {"", "-", ".", "1.2.3", "+1", "1e5", "nan", "inf", "1,5", "--1", "1-"})
      CHECK_MESSAGE(!parse_plain_decimal(bad, v), bad);
    // Past 15 significant digits the slow path reads it: 2^53 + 1 rounds to even.
    CHECK(parse_plain_decimal("9007199254740993", v));
    CHECK(v == 9007199254740992.0);
    // Too large for a finite double.
    CHECK(!parse_plain_decimal(std::string(400, '9'), v));
  }
}
