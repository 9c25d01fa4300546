#include "freeturn/post/nc_guard.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <system_error>

#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

// ASCII classes: every byte check_line classifies is printable ASCII by then, and the C
// library's (locale-dependent, one call a byte) would cost more than the rest of the guard.
constexpr bool ascii_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
constexpr char ascii_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }
constexpr char ascii_upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; }

}  // namespace

NcGuard::NcGuard(const MachineDescription& machine) {
  for (const AxisSpec& s : machine.axes) {
    const char letter = axis_letter(s.axis)[0];
    Range& r = ranges_[letter - 'A'];
    const double half_unit = 0.5 * std::pow(10.0, -s.decimals);
    if (s.axis == Axis::kC) {
      if (!machine.c_wrapped) continue;  // accumulating: any finite angle
      r = {true, -half_unit, 360 + half_unit};
    } else if (s.axis == Axis::kB) {
      r = {true, std::max(s.min, machine.b_min_deg) - half_unit, std::min(s.max, machine.b_max_deg) + half_unit};
    } else {
      r = {true, s.min - half_unit, s.max + half_unit};
    }
  }
}

std::string NcGuard::check_record(const AxisRecord& record, long long block) const {
  const std::pair<char, double> values[] = {{'X', record.x}, {'Z', record.z}, {'C', record.c}, {'B', record.b}};
  std::string why = "block ";
  why += std::to_string(block);
  why += ": ";
  if (!std::isfinite(record.time) || record.time < 0) {
    why += "block time ";
    why += shortest_text(record.time);
    why += " s is not a finite duration";
    return why;
  }
  for (const auto& [letter, v] : values) {
    const Range& r = ranges_[letter - 'A'];
    const bool outside = letter != 'C' && r.checked && (v < r.min || v > r.max);
    if (std::isfinite(v) && !outside) continue;
    why += letter;
    why += " = ";
    why += shortest_text(v);
    why += std::isfinite(v) ? " is outside its travel [" + shortest_text(r.min) + ", " + shortest_text(r.max) + "]"
                            : std::string(" is not a finite number");
    return why;
  }
  return {};
}

void NcGuard::select_file(std::size_t index, const std::string& name) {
  if (files_.size() <= index) files_.resize(index + 1);
  if (files_[index].name.empty()) files_[index].name = name;
  current_ = index;
}

void NcGuard::feed(std::string_view bytes) {
  if (files_.empty()) select_file(0, "program");
  File& f = files_[current_];
  f.bytes += static_cast<long long>(bytes.size());
  while (!bytes.empty()) {
    const std::size_t newline = bytes.find('\n');
    if (newline == std::string_view::npos) {
      f.line.append(bytes);
      return;
    }
    f.line.append(bytes.substr(0, newline));
    bytes.remove_prefix(newline + 1);
    ++f.lines;
    check_line(f.line);
    f.line.clear();
  }
}

void NcGuard::end_files() {
  for (std::size_t k = 0; k < files_.size(); ++k) {
    if (files_[k].line.empty()) continue;
    current_ = k;
    ++files_[k].lines;
    check_line(files_[k].line);
    files_[k].line.clear();
  }
}

void NcGuard::refuse(const std::string& what) {
  if (!reason_.empty()) return;
  reason_ = files_[current_].name;
  reason_ += ":";
  reason_ += std::to_string(files_[current_].lines);
  reason_ += ": ";
  reason_ += what;
}

void NcGuard::check_line(std::string_view line) {
  // Text only, comments included: a controller reads every byte of a line.
  for (std::size_t i = 0; i < line.size(); ++i) {
    const unsigned char ch = static_cast<unsigned char>(line[i]);
    if ((ch < 0x20 && ch != '\t' && ch != '\r') || ch > 0x7E) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X", ch);
      return refuse("byte " + std::string(code) + " at column " + std::to_string(i + 1) +
                    " is not printable ASCII");
    }
  }
  // The words outside comments: "( … )" and everything after ';'.
  std::string& code = code_;
  code.clear();
  int depth = 0;
  for (const char ch : line) {
    if (ch == ';' && depth == 0) break;
    if (ch == '(') ++depth;
    else if (ch == ')' && depth > 0) --depth;
    else if (depth == 0) code += ascii_lower(ch);
  }
  if (code.find("nan") != std::string::npos || code.find("inf") != std::string::npos)
    return refuse("a number that is not finite: " + std::string(line));
  // Machine-coordinate moves (G53), reference returns (G28, G30) and position presets
  // (G92) are not in the work frame the travel is given in: their numbers need only be
  // finite.
  bool work_frame = true;
  for (const char* code_word : {"g53", "g28", "g30", "g92"}) {
    for (std::size_t at = code.find(code_word); at != std::string::npos; at = code.find(code_word, at + 1)) {
      const std::size_t after = at + 3;
      if (after >= code.size() || !ascii_digit(code[after])) work_frame = false;
    }
  }
  for (std::size_t i = 0; i < code.size(); ++i) {
    if (!ascii_letter(code[i])) continue;
    std::size_t j = i + 1;
    if (j < code.size() && (code[j] == '-' || code[j] == '+')) ++j;
    const std::size_t digits = j;
    while (j < code.size() && (ascii_digit(code[j]) || code[j] == '.')) ++j;
    if (j == digits) {
      // A keyword's letter, unless it stands alone: then it is a word whose number is
      // missing or is not a number ("F" then garbage).
      const bool alone = (i == 0 || !ascii_letter(code[i - 1])) &&
                         (j >= code.size() || !ascii_letter(code[j]));
      if (alone && std::string_view("xzcbf").find(code[i]) != std::string_view::npos)
        return refuse(std::string(1, ascii_upper(code[i])) +
                      " without a number after it: " + std::string(line));
      continue;
    }
    const char letter = ascii_upper(code[i]);
    std::string_view number(code.data() + i + 1, j - i - 1);
    if (!number.empty() && number.front() == '+') number.remove_prefix(1);
    double v = 0;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), v);
    const auto word = [&] { return std::string(1, letter) + std::string(number); };
    if (error != std::errc() || end != number.data() + number.size() || !std::isfinite(v))
      return refuse(word() + " is not a number");
    const Range& r = ranges_[letter - 'A'];
    if (work_frame && r.checked && (v < r.min || v > r.max)) {
      crossed_ = {letter, v > r.max};
      return refuse(word() + " is outside the machine's range [" + shortest_text(r.min) + ", " +
                    shortest_text(r.max) + "]");
    }
    i = j - 1;
  }
}

}  // namespace freeturn
