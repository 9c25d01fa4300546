#include <doctest/doctest.h>

#include <random>
#include <string>

#include "freeturn/io/nc_line.hpp"

using namespace freeturn;

namespace {

// The classes by the rule as NcLineBytes states it, one byte at a time.
NcLineBytes classes_byte_by_byte(const std::string& line) {
  NcLineBytes c;
  for (const char ch : line) {
    const int byte = static_cast<unsigned char>(ch);
    if ((byte < 32 && byte != 9 && byte != 13) || byte > 126) c.unprintable = true;
    if (ch == '(' || ch == ')' || ch == ';') c.comment_marks = true;
  }
  return c;
}

}  // namespace

TEST_SUITE("io") {
  TEST_CASE("classify_nc_bytes: the classes of every byte value, at every place in a word") {
    // Each byte value alone among plain text, at each of 19 places (both words of a 16-byte
    // stretch and the tail after them).
    for (int value = 0; value < 256; ++value)
      for (std::size_t at = 0; at < 19; ++at) {
        std::string line = "C4.00000 X0.791994 Z";
        line[at] = static_cast<char>(value);
        const NcLineBytes want = classes_byte_by_byte(line), got = classify_nc_bytes(line);
        CAPTURE(value);
        CAPTURE(at);
        CHECK(got.unprintable == want.unprintable);
        CHECK(got.comment_marks == want.comment_marks);
      }
  }

  TEST_CASE("classify_nc_bytes: random lines of the bytes at the classes' edges") {
    // The values next to each edge (0, tab, CR, ' ', '~', DEL, 128, 255, the marks, and the
    // bytes one either side of a mark, whose xor with it is 1), where a word-wide borrow
    // could flag the wrong byte.
    const unsigned char edges[] = {0,   1,   8,   9,   10,  12,  13,  14,  31,  32, 33,
                                   39,  40,  41,  42,  58,  59,  60,  48,  57,  65, 126,
                                   127, 128, 129, 160, 254, 255, 'X', 'Z', '.', '-'};
    std::mt19937 random(20261208);
    std::uniform_int_distribution<std::size_t> pick(0, sizeof edges - 1), length(0, 40);
    std::uniform_int_distribution<int> plain(0, 9);
    long differing = 0, unprintable = 0, marked = 0;
    for (int n = 0; n < 200000; ++n) {
      std::string line(length(random), 'X');
      // Mostly plain text, a few edge bytes: lines where only one word is flagged.
      for (char& ch : line)
        ch = plain(random) < 8 ? static_cast<char>('0' + plain(random))
                               : static_cast<char>(edges[pick(random)]);
      const NcLineBytes want = classes_byte_by_byte(line), got = classify_nc_bytes(line);
      differing += got.unprintable != want.unprintable || got.comment_marks != want.comment_marks;
      unprintable += want.unprintable;
      marked += want.comment_marks;
    }
    CHECK(differing == 0);
    // Both answers occur both ways: the lines test something.
    CHECK(unprintable > 10000);
    CHECK(unprintable < 190000);
    CHECK(marked > 10000);
    CHECK(marked < 190000);
  }
}
