#include "freeturn/core/parallel_for.hpp"

#include <algorithm>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "freeturn/core/error.hpp"

namespace freeturn {

int thread_count(int requested) {
  if (requested < 0 || requested > kMaxThreads)
    throw InputError("threads", "must be 0 (one per hardware thread) or 1 to " +
                                    std::to_string(kMaxThreads) + ", not " +
                                    std::to_string(requested));
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void parallel_for(int threads, long count, const std::function<void(long, long)>& body) {
  if (count <= 0) return;
  const long parts = std::clamp<long>(threads, 1, count);
  if (parts == 1) {
    body(0, count);
    return;
  }
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(parts));
  const auto run = [&](long part) {
    try {
      body(count * part / parts, count * (part + 1) / parts);
    } catch (...) {
      errors[static_cast<std::size_t>(part)] = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(parts - 1));
  for (long part = 1; part < parts; ++part) workers.emplace_back(run, part);
  run(0);
  for (std::thread& w : workers) w.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace freeturn
