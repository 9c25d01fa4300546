#pragma once
// Numbers in the report's words and JSON: 9 significant digits, "null" for what is not
// finite (JSON has no NaN). Internal to pipeline/.

#include <cmath>
#include <cstdio>
#include <string>

namespace freeturn::detail {

inline std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace freeturn::detail
