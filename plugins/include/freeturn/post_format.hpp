#pragma once
// Number formatting for post-processors (C++ plugins, header only): fixed decimals,
// correctly rounded (std::to_chars), no locale, no iostream, never "-0" or NaN.

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace freeturn::post {

// The room a formatted number may take, its terminator included: any NC word freeturn
// writes fits (a travel of metres at 12 decimals is 20 characters).
constexpr int kNumberCapacity = 48;
// The decimals a word may carry.
constexpr int kMaxDecimals = 15;

// 10^decimals, exact, for decimals in [0, kMaxDecimals] (a table: std::pow costs more than
// the rest of a word's formatting).
inline double decimal_scale(int decimals) {
  static constexpr double kScale[kMaxDecimals + 1] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                      1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  return kScale[decimals];
}

// Writes the integer n (|n| < 4e15) as n / 10^decimals with `decimals` digits after the
// point, never "-0": the digits from the right, two at a time, then the point moved into
// place.
inline int format_scaled_integer(double n, int decimals, char* out) {
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  unsigned long long digits = static_cast<unsigned long long>(std::abs(n));
  char reversed[24];
  int count = 0;
  while (digits >= 100) {
    const unsigned pair = static_cast<unsigned>(digits % 100);
    digits /= 100;
    reversed[count++] = kPairs[2 * pair + 1];
    reversed[count++] = kPairs[2 * pair];
  }
  do {
    reversed[count++] = static_cast<char>('0' + digits % 10);
    digits /= 10;
  } while (digits != 0);
  while (count <= decimals) reversed[count++] = '0';  // a digit before the point at least
  int length = 0;
  if (n < 0) out[length++] = '-';
  for (int k = count - 1; k >= decimals; --k) out[length++] = reversed[k];
  if (decimals > 0) {
    out[length++] = '.';
    for (int k = decimals - 1; k >= 0; --k) out[length++] = reversed[k];
  }
  return length;
}

// Writes `value` with `decimals` digits after the point into `out` (kNumberCapacity
// bytes) and returns the length; 0 for NaN or infinity, for decimals outside
// [0, kMaxDecimals], and for a value too long to fit (1e300 in fixed notation). Never
// writes past out + kNumberCapacity − 1, and never leaves a byte it did not mean.
inline int format_fixed(double value, int decimals, char* out) {
  if (!std::isfinite(value) || decimals < 0 || decimals > kMaxDecimals) return 0;
  // Fast path, the same text as std::to_chars: X = value·10^decimals as p + r exactly (the
  // scale is an exact double, and an FMA gives the product's rounding error r exactly);
  // n, the integer nearest p, is the correctly rounded X unless X lies within 1e-6 of a
  // half, where a tie or a rounding of p could decide it: that goes to to_chars.
  const double scale = decimal_scale(decimals);
  const double p = value * scale;
  if (std::abs(p) < 4e15) {
    const double r = std::fma(value, scale, -p);
    const double n = std::nearbyint(p);
    const double fraction = (p - n) + r;  // p − n is exact below 2^52
    if (std::abs(fraction) < 0.5 - 1e-6) {
      return format_scaled_integer(value < 0 ? -std::abs(n) : std::abs(n), decimals, out);
    }
  }
  const auto [end, error] =
      std::to_chars(out, out + kNumberCapacity - 1, value, std::chars_format::fixed, decimals);
  if (error != std::errc()) return 0;
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
  if (!std::isfinite(value) || decimals < 0 || decimals > kMaxDecimals) return 0;
  const double scale = decimal_scale(decimals);
  const double n = std::nearbyint(value * scale);
  // The text of the rounded angle, wrapped below, is n's own (or n − 360·10^d's) digits:
  // printing n / 10^d at d decimals gives back n. Up to 12 decimals n / 10^d ≥ 360
  // exactly when n ≥ 360·10^d (a unit of the last place is far above 360's rounding).
  if (decimals <= 12 && std::abs(n) < 4e15)
    return format_scaled_integer(n >= 360 * scale ? n - 360 * scale : n, decimals, out);
  double rounded = n / scale;
  if (rounded >= 360.0) rounded -= 360.0;
  return format_fixed(rounded, decimals, out);
}

// Why a number cannot be written: thrown by the append functions (the plugin adapter turns
// it into the plugin's refusal; nothing is written).
inline std::range_error unwritable(char letter, double value, int decimals) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text - 1, value);  // locale-free
  *(written.ec == std::errc() ? written.ptr : text) = '\0';
  return std::range_error(std::string(letter ? std::string(1, letter) + " " : "a number ") + text +
                          " cannot be written with " + std::to_string(decimals) +
                          " decimals (not finite, or too long for an NC word)");
}

// Writes `letter` and the value (fixed decimals; C wrapped when `wrapped`) into `out`
// (room for kNumberCapacity + 1 bytes) and returns the length. Throws std::range_error
// when the value cannot be written (format_fixed).
inline int format_word(char letter, double value, int decimals, bool wrapped, char* out) {
  out[0] = letter;
  const int n = wrapped ? format_wrapped_degrees(value, decimals, out + 1)
                        : format_fixed(value, decimals, out + 1);
  if (n == 0) throw unwritable(letter, value, decimals);
  return n + 1;
}

// Appends `letter` and the value (fixed decimals; C wrapped when `wrapped`) to `line`.
// Throws std::range_error when the value cannot be written (format_fixed).
inline void append_word(std::string& line, char letter, double value, int decimals,
                        bool wrapped = false) {
  char buf[kNumberCapacity + 1];
  line.append(buf, static_cast<std::size_t>(format_word(letter, value, decimals, wrapped, buf)));
}

// Appends the value alone (fixed decimals). Throws std::range_error as append_word does.
inline void append_number(std::string& line, double value, int decimals) {
  char buf[kNumberCapacity];
  const int n = format_fixed(value, decimals, buf);
  if (n == 0) throw unwritable(0, value, decimals);
  line.append(buf, static_cast<std::size_t>(n));
}

// The height to approach and retract at (ft_program_info: top_z, z_away): `retract` beyond
// the clearance base, rounded away from the part at `decimals` so that the written word is
// never nearer the part than asked.
inline double clearance_z(double top_z, int z_away, double retract, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double z = (top_z + z_away * retract) * scale;
  return (z_away > 0 ? std::ceil(z) : std::floor(z)) / scale;
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
