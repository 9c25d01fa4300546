#include <doctest/doctest.h>

#include <thread>

#include "freeturn/core/error.hpp"
#include "freeturn/core/parallel_for.hpp"

using freeturn::InputError;
using freeturn::thread_count;

TEST_SUITE("core") {
  TEST_CASE("thread_count: 0 is the hardware's threads, 1 to 1024 as asked, anything else refused") {
    const int hardware = static_cast<int>(std::thread::hardware_concurrency());
    CHECK(thread_count(0) == (hardware > 0 ? hardware : 1));
    CHECK(thread_count(1) == 1);
    CHECK(thread_count(1024) == 1024);
    // A typo of 100 000 would start that many threads; a negative count means nothing.
    CHECK_THROWS_WITH_AS(thread_count(100000),
                         "threads: must be 0 (one per hardware thread) or 1 to 1024, not 100000",
                         InputError);
    CHECK_THROWS_WITH_AS(thread_count(-5), doctest::Contains("not -5"), InputError);
    CHECK_THROWS_AS(thread_count(1025), InputError);
  }
}
