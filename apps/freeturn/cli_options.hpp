#pragma once
// Option values parsed whole: "0.5x", "" and out-of-range numbers are refused with the
// option's name, never read as far as they go (atoi/atof) or overflowed.

#include <cmath>
#include <cstdlib>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/job/yaml_limits.hpp"

namespace freeturn::cli {

// A whole number in [lo, hi]; `what` completes "must be …" in the error.
inline long option_integer(const std::string& option, const std::string& text, long lo, long hi,
                           const std::string& what) {
  char* end = nullptr;
  const long n = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || n < lo || n > hi)
    throw InputError(option, "must be " + what + ", not '" + text + "'");
  return n;
}

// A finite length > 0 (mm).
inline double option_length(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v > 0) || !std::isfinite(v))
    throw InputError(option, "must be a length > 0 (mm), not '" + text + "'");
  return v;
}

// The bound on a job or machine file's size before it is parsed: FREETURN_MAX_YAML_MB
// (a number of MiB from 0.001 to 1024) when set, else the kernel's default (4 MiB).
inline std::uintmax_t yaml_byte_bound() {
  const char* v = std::getenv("FREETURN_MAX_YAML_MB");
  if (v == nullptr) return kMaxYamlBytes;
  char* end = nullptr;
  const double mb = std::strtod(v, &end);
  if (*v == '\0' || *end != '\0' || !(mb >= 0.001 && mb <= 1024))
    throw InputError("FREETURN_MAX_YAML_MB",
                     "must be a size in MiB from 0.001 to 1024, not '" + std::string(v) + "'");
  return static_cast<std::uintmax_t>(mb * 1048576.0);
}

}  // namespace freeturn::cli
