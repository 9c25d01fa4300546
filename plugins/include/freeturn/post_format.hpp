#pragma once
// Number formatting for post-processors (C++ plugins, header only): fixed decimals,
// correctly rounded (std::to_chars), no locale, no iostream, never "-0" or NaN.

#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

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

// Appends `letter` and the value (fixed decimals; C wrapped when `wrapped`) to `line`.
// Returns false for NaN or infinity.
inline bool append_word(std::string& line, char letter, double value, int decimals,
                        bool wrapped = false) {
  char buf[48];
  const int n = wrapped ? format_wrapped_degrees(value, decimals, buf) : format_fixed(value, decimals, buf);
  if (n == 0) return false;
  line.push_back(letter);
  line.append(buf, static_cast<std::size_t>(n));
  return true;
}

// Appends the value alone (fixed decimals). Returns false for NaN or infinity.
inline bool append_number(std::string& line, double value, int decimals) {
  char buf[48];
  const int n = format_fixed(value, decimals, buf);
  if (n == 0) return false;
  line.append(buf, static_cast<std::size_t>(n));
  return true;
}

// A setting's value as written in the machine YAML: "\n" is a line break, "\\" a
// backslash (the host escapes both so that each setting stays on one line).
inline std::string unescape_lines(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == 'n' || s[i + 1] == '\\')) {
      out.push_back(s[i + 1] == 'n' ? '\n' : '\\');
      ++i;
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

}  // namespace freeturn::post
