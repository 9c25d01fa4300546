#pragma once
// Outcomes of numerical routines that are expected and must be handled by the caller.
// Routines return them beside their value and never throw for them.

namespace freeturn {

enum class Status {
  kOk,            // converged to the requested tolerance
  kNotConverged,  // iteration limit reached; the value is the best found
  kMissed,        // a ray or projection does not meet the surface
  kDegenerate,    // the problem has no unique answer (zero-length tangent, parallel ray)
};

constexpr const char* to_string(Status s) {
  switch (s) {
    case Status::kOk:
      return "ok";
    case Status::kNotConverged:
      return "not converged";
    case Status::kMissed:
      return "missed";
    case Status::kDegenerate:
      return "degenerate";
  }
  return "unknown";
}

}  // namespace freeturn
