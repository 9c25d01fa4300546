#pragma once
// The bound on a job or machine file, checked before it is parsed (docs/robustness.md).

#include <cstdint>

namespace freeturn {

// Bytes. The largest real job, with an inline NURBS of a few thousand control points, is
// tens of kilobytes; /dev/zero or a pasted log is refused before a byte is parsed.
constexpr std::uintmax_t kMaxYamlBytes = 4u << 20;

// Levels of nesting: a job's deepest map is a few levels; a spec built in memory (Python's
// surface(dict)) is held to the same, so that one that holds itself is refused.
constexpr int kMaxYamlDepth = 64;

}  // namespace freeturn
