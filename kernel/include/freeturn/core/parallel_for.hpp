#pragma once
// Splitting a loop over contiguous ranges among threads, the simplest parallelism that
// stays deterministic: each range's work is fixed by the count and thread number alone,
// and a caller that reduces per-range results in range order gets the same answer on any
// number of threads.

#include <functional>

#include "freeturn/core/thread_limits.hpp"

namespace freeturn {

// The hardware's threads (at least 1) for 0, or `requested` from 1 to kMaxThreads; any
// other number is an InputError at "threads".
int thread_count(int requested);

// Runs body(begin, end) over [0, count) split into at most `threads` contiguous ranges,
// the first on the calling thread. If bodies throw, the exception of the lowest range is
// rethrown after all have finished.
void parallel_for(int threads, long count, const std::function<void(long begin, long end)>& body);

}  // namespace freeturn
