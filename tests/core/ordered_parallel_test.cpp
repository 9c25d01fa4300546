#include <doctest/doctest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "freeturn/core/ordered_parallel.hpp"

using namespace freeturn;

TEST_SUITE("core") {
  TEST_CASE("ordered_parallel: items consumed in order, at most a window ahead, on any thread count") {
    for (int threads : {1, 2, 8}) {
      std::atomic<long> consumed{0}, worst_lead{0};
      std::vector<long> order;
      ordered_parallel<std::vector<long>>(
          threads, 500, 2 * threads,
          [&](long i, std::vector<long>& slot) {
            // How far ahead of the consumer this item is made.
            const long lead = i - consumed.load();
            long seen = worst_lead.load();
            while (lead > seen && !worst_lead.compare_exchange_weak(seen, lead)) {
            }
            slot.assign(static_cast<std::size_t>(i % 7 + 1), i * i);
          },
          [&](long i, std::vector<long>& slot) {
            CHECK(slot.size() == static_cast<std::size_t>(i % 7 + 1));
            CHECK(slot.front() == i * i);
            order.push_back(i);
            ++consumed;
          });
      REQUIRE(order.size() == 500);
      for (long i = 0; i < 500; ++i) CHECK(order[static_cast<std::size_t>(i)] == i);
      CHECK(worst_lead.load() <= std::max(2 * threads, threads));
    }
  }

  TEST_CASE("ordered_parallel: the first failure in order is the one rethrown") {
    for (int threads : {1, 2, 4}) {
      long consumed = 0;
      CHECK_THROWS_WITH(ordered_parallel<int>(
                            threads, 100, 8,
                            [](long i, int& slot) {
                              if (i == 37 || i == 60) throw std::runtime_error("item " + std::to_string(i));
                              slot = static_cast<int>(i);
                            },
                            [&](long i, int& slot) {
                              CHECK(slot == i);
                              ++consumed;
                            }),
                        "item 37");
      CHECK(consumed == 37);
    }
  }
}
