#pragma once
// Settings of the command line that come from the environment (its options are CLI11's,
// declared in main.cpp).

#include <cmath>
#include <cstdlib>
#include <string>

#include "freeturn/freeturn.hpp"

namespace freeturn::cli {

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
