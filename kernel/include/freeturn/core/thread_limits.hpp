#pragma once
// The bound on the threads a caller may ask for (docs/robustness.md).

namespace freeturn {

// The command line's --threads and the library's RunOptions::threads alike: 0 is one per
// hardware thread, 1 to this as asked. A typo of 100 000 would start that many threads.
inline constexpr int kMaxThreads = 1024;

}  // namespace freeturn
