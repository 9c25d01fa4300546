#include <doctest/doctest.h>

#include "freeturn/core/error.hpp"
#include "freeturn/core/status.hpp"

using freeturn::InputError;
using freeturn::SourceLocation;

TEST_SUITE("core") {
  TEST_CASE("InputError puts the place before the problem") {
    const InputError e(SourceLocation{"job.yaml", 3, 7}, "radius must be greater than 0");
    CHECK(std::string(e.what()) == "job.yaml:3:7: radius must be greater than 0");
    CHECK(e.where() == "job.yaml:3:7");
    CHECK(e.problem() == "radius must be greater than 0");
  }

  TEST_CASE("SourceLocation prints only what is known") {
    CHECK(SourceLocation{"a.yaml", 0, 0}.to_string() == "a.yaml");
    CHECK(SourceLocation{"a.yaml", 4, 0}.to_string() == "a.yaml:4");
    CHECK(SourceLocation{"", 0, 0}.to_string().empty());
    CHECK(std::string(InputError("plain").what()) == "plain");
    CHECK(std::string(InputError("theta=1.5 rad, r=2 mm", "missed").what()) ==
          "theta=1.5 rad, r=2 mm: missed");
  }

  TEST_CASE("InputError escapes control bytes quoted from a file") {
    // A NUL, an escape sequence and a carriage return from a scalar, written byte by byte.
    const std::string scalar{'a', '\0', '\x1b', '[', '3', '1', 'm', '\r', 'b', '\x7f'};
    const InputError e("job\n.yaml:1:7", "unknown type '" + scalar + "'\n(second line)");
    CHECK(e.where() == "job\\x0a.yaml:1:7");
    CHECK(e.problem() == "unknown type 'a\\x00\\x1b[31m\\x0db\\x7f'\n(second line)");
    CHECK(freeturn::escape_control_bytes("a\tb\n") == "a\\x09b\\x0a");
    CHECK(freeturn::escape_control_bytes("a\tb\n", true) == "a\\x09b\n");
    // U+202E (right-to-left override, E2 80 AE), U+009B (8-bit CSI, C2 9B), U+2066 (E2 81
    // A6); U+00E9 (C3 A9) and U+2014 (E2 80 94) are shown as they are.
    CHECK(freeturn::escape_control_bytes("pl\xe2\x80\xae"
                                         "ate") == "pl\\u202eate");
    CHECK(freeturn::escape_control_bytes("\xc2\x9b"
                                         "2J") == "\\u009b2J");
    CHECK(freeturn::escape_control_bytes("a\xe2\x81\xa6"
                                         "b") == "a\\u2066b");
    CHECK(freeturn::escape_control_bytes("caf\xc3\xa9 \xe2\x80\x94") == "caf\xc3\xa9 \xe2\x80\x94");
    // A sequence cut short at the end is left as it is (the reader has refused bad UTF-8).
    CHECK(freeturn::escape_control_bytes("a\xe2\x80") == "a\xe2\x80");
    // Escaping twice changes nothing: a message re-thrown with more text stays readable.
    CHECK(InputError(e.where(), e.problem()).problem() == e.problem());
  }

  TEST_CASE("Status names") {
    CHECK(std::string(freeturn::to_string(freeturn::Status::kNotConverged)) == "not converged");
    CHECK(std::string(freeturn::to_string(freeturn::Status::kMissed)) == "missed");
  }
}
