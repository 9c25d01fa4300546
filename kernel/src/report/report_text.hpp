#pragma once
// Numbers in report.json and report.html: 9 significant digits, locale-free, "null" for
// what is not finite (JSON has no NaN). Internal to report/.

#include <cmath>
#include <string>

#include "freeturn/core/number_text.hpp"

namespace freeturn::detail {

inline std::string num(double v) { return std::isfinite(v) ? significant_text(v, 9) : "null"; }

}  // namespace freeturn::detail
