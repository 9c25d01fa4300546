#pragma once
// Numbers read from text files, all or nothing: the whole field must be the number, and
// it must be finite. std::stod/stoi throw std::invalid_argument and std::out_of_range,
// which would escape the readers' InputError; std::from_chars reports instead.
// Numbers written as text go through std::to_chars too: neither way depends on the
// process's locale (a German LC_NUMERIC makes printf write "1,25").

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>

namespace freeturn {

inline bool parse_finite(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

// Any number from_chars reads whole, NaN and infinity included.
inline bool parse_number(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

// A number as NC words and tables write it: an optional '-', digits and at most one '.'
// (no sign '+', exponent, "nan" or "inf"); false for anything else. The value is what
// std::from_chars reads, to the bit. Most such numbers have at most 15 significant digits
// and 22 decimals: then the digits m and 10^e are exact doubles and m / 10^e, one
// correctly rounded division, is the correctly rounded value (Clinger's fast path, "How
// to read floating point numbers accurately", 1990), several times faster than
// from_chars, which reads the rest.
inline bool parse_plain_decimal(std::string_view text, double& value) {
  std::size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative) ++i;
  unsigned long long mantissa = 0;
  int significant = 0, decimals = 0, digits = 0;
  bool point = false;
  for (; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '.') {
      if (point) return false;
      point = true;
      continue;
    }
    if (ch < '0' || ch > '9') return false;
    ++digits;
    decimals += point;
    if (mantissa == 0 && ch == '0') continue;  // leading zeros are not significant
    if (++significant <= 15) mantissa = mantissa * 10 + static_cast<unsigned long long>(ch - '0');
  }
  if (digits == 0) return false;
  if (significant <= 15 && decimals <= 22) {
    // The fast path: a mantissa below 10^15 and a power of ten up to 10^22 are both exact
    // doubles, so their correctly rounded quotient is the number's nearest double.
    static constexpr double kPowers[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                         1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                         1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const double magnitude = static_cast<double>(mantissa) / kPowers[decimals];
    value = negative ? -magnitude : magnitude;
    return true;
  }
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

inline bool parse_int(std::string_view text, int& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

// The shortest text that reads back as the same double ("0.1", "1e-07", "nan", "inf").
inline std::string shortest_text(double value) {
  char buf[32];
  const auto [end, error] = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, error == std::errc() ? end : buf);
}

// `digits` significant digits, as printf's %.<digits>g writes them in the C locale.
inline std::string significant_text(double value, int digits) {
  char buf[64];
  const auto [end, error] =
      std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, digits);
  return std::string(buf, error == std::errc() ? end : buf);
}

// `decimals` digits after the point, as printf's %.<decimals>f writes them in the C locale.
inline std::string fixed_text(double value, int decimals) {
  char buf[384];
  const auto [end, error] =
      std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
  return std::string(buf, error == std::errc() ? end : buf);
}

}  // namespace freeturn
