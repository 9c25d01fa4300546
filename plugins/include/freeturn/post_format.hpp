#pragma once
// Number formatting for post-processors (C++ plugins, header only): fixed decimals,
// correctly rounded (std::to_chars), no locale, no iostream, never "-0" or NaN.

#include <charconv>
#include <cmath>
#include <cstring>

namespace freeturn::post {

// Writes `value` with `decimals` digits after the point into `out` (at least 40 bytes)
// and returns the length, or 0 for NaN or infinity.
inline int format_fixed(double value, int decimals, char* out) {
  if (!std::isfinite(value)) return 0;
  char* end = std::to_chars(out, out + 40, value, std::chars_format::fixed, decimals).ptr;
  int n = static_cast<int>(end - out);
  // "-0.000" after rounding is 0.
  if (out[0] == '-') {
    bool zero = true;
    for (int i = 1; i < n; ++i)
      if (out[i] != '0' && out[i] != '.') zero = false;
    if (zero) {
      std::memmove(out, out + 1, static_cast<std::size_t>(n - 1));
      --n;
    }
  }
  return n;
}

// C in [0, 360) at `decimals`: a value that rounds to 360 is written as 0.
inline int format_wrapped_degrees(double value, int decimals, char* out) {
  const double scale = std::pow(10.0, decimals);
  double rounded = std::nearbyint(value * scale) / scale;
  if (rounded >= 360.0) rounded -= 360.0;
  return format_fixed(rounded, decimals, out);
}

}  // namespace freeturn::post
