#include <doctest/doctest.h>

#include <string>

#include "freeturn/core/utf8.hpp"

using namespace freeturn;

TEST_SUITE("core") {
  TEST_CASE("utf8_length follows RFC 3629's table of well-formed sequences") {
    CHECK(utf8_length("a", 0) == 1);
    CHECK(utf8_length("\xc3\xbc", 0) == 2);              // ü
    CHECK(utf8_length("\xe2\x82\xac", 0) == 3);          // €
    CHECK(utf8_length("\xf0\x9f\x98\x80", 0) == 4);      // U+1F600
    CHECK(utf8_length("\xf4\x8f\xbf\xbf", 0) == 4);      // U+10FFFF, the last
    CHECK(utf8_length("\xfc", 0) == 0);                  // Latin-1 ü
    CHECK(utf8_length("\xc0\x80", 0) == 0);              // overlong NUL
    CHECK(utf8_length("\xe0\x9f\xbf", 0) == 0);          // overlong U+07FF
    CHECK(utf8_length("\xed\xa0\x80", 0) == 0);          // a surrogate, U+D800
    CHECK(utf8_length("\xf4\x90\x80\x80", 0) == 0);      // past U+10FFFF
    CHECK(utf8_length("\x80", 0) == 0);                  // a lone continuation byte
    CHECK(utf8_length("\xe2\x82", 0) == 0);              // truncated at the end
  }

  TEST_CASE("valid_utf8 keeps UTF-8 and replaces each stray byte by U+FFFD") {
    CHECK(valid_utf8("f\xc3\xbcr") == "f\xc3\xbcr");
    CHECK(valid_utf8("f\xfcr") == "f\xef\xbf\xbdr");
    CHECK(valid_utf8("\xe2\x82") == "\xef\xbf\xbd\xef\xbf\xbd");
  }
}
