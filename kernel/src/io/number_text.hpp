#pragma once
// Numbers read from text files, all or nothing: the whole field must be the number, and
// it must be finite. std::stod/stoi throw std::invalid_argument and std::out_of_range,
// which would escape the readers' InputError; std::from_chars reports instead.
// Internal to io/.

#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

namespace freeturn::detail {

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

}  // namespace freeturn::detail
