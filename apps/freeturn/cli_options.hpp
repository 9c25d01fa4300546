#pragma once
// Option values parsed whole: "0.5x", "" and out-of-range numbers are refused with the
// option's name, never read as far as they go (atoi/atof) or overflowed.

#include <cmath>
#include <cstdlib>
#include <string>

#include "freeturn/core/error.hpp"

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

}  // namespace freeturn::cli
