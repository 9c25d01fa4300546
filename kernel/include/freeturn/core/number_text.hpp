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
