#pragma once
// The dialect settings a plugin receives: the flat map under its key in the machine file,
// as "key: value" lines, one per key, with line breaks and backslashes in a value escaped
// as \n and \\ (unescape_lines in post_format.hpp restores them). This header-only reader
// is for them. A key the plugin does not know is an error, as in every other YAML
// freeturn reads.

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <string>
#include <system_error>

#include "freeturn/post_format.hpp"

namespace freeturn::post {

class FlatSettings {
 public:
  // Returns false with a message on a line that is not `key: value`.
  bool parse(const char* text, std::string& error) {
    std::string s(text ? text : "");
    std::size_t start = 0;
    int line = 0;
    while (start < s.size()) {
      std::size_t end = s.find('\n', start);
      if (end == std::string::npos) end = s.size();
      std::string l = s.substr(start, end - start);
      start = end + 1;
      ++line;
      const std::size_t first = l.find_first_not_of(" \t\r");
      if (first == std::string::npos) continue;
      const std::size_t colon = l.find(':');
      if (colon == std::string::npos) {
        error = "dialect settings line " + std::to_string(line) + " is not 'key: value'";
        return false;
      }
      std::string key = trim(l.substr(0, colon)), value = trim(l.substr(colon + 1));
      values_[key] = value;
    }
    return true;
  }

  std::string text(const std::string& key, const std::string& fallback) {
    used_[key] = true;
    const auto it = values_.find(key);
    return it == values_.end() ? fallback : it->second;
  }
  // False (with a message) when the value is not a number.
  bool number(const std::string& key, double fallback, double& out, std::string& error) {
    const std::string v = text(key, "");
    if (v.empty()) {
      out = fallback;
      return true;
    }
    // std::from_chars, not strtod: a host program in a German locale would have strtod stop
    // at the '.' of "1.0".
    const char* first = v.data() + (v[0] == '+' ? 1 : 0);
    const char* last = v.data() + v.size();
    const auto [end, ec] = std::from_chars(first, last, out);
    if (first == last || ec != std::errc() || end != last || !std::isfinite(out)) {
      error = "dialect setting '" + key + "' must be a number, not '" + v + "'";
      return false;
    }
    return true;
  }
  // A number within [lo, hi] (a fallback outside it is the plugin's own fault).
  bool number_in(const std::string& key, double fallback, double lo, double hi, double& out,
                 std::string& error) {
    if (!number(key, fallback, out, error)) return false;
    if (out >= lo && out <= hi) return true;
    error = "dialect setting '" + key + "' is " + text(key, "") + ", outside [" + shortest(lo) +
            ", " + shortest(hi) + "]";
    return false;
  }
  // A whole number within [lo, hi].
  bool whole_number_in(const std::string& key, double fallback, double lo, double hi, double& out,
                       std::string& error) {
    if (!number_in(key, fallback, lo, hi, out, error)) return false;
    if (out == std::floor(out)) return true;
    error = "dialect setting '" + key + "' must be a whole number, not " + text(key, "");
    return false;
  }
  // Lines of codes for the controller (a header, a footer), "\n" between lines: printable
  // ASCII only. The guard would refuse such a byte in the program anyway; here the refusal
  // names the setting, which the host places in the machine file.
  // Nor may a line give X or Z in the work frame (an X, Z, U or W word on a line without
  // G53): the program's own approach and retract stay clear of the part, and a header's or
  // footer's move would not ("G00 X0 Z-0.5" after the retract plunges into the part's
  // centre). Parking goes by machine coordinates (G53).
  bool code_lines(const std::string& key, const std::string& fallback, std::string& out,
                  std::string& error) {
    out = unescape_lines(text(key, fallback));
    for (const char ch : out) {
      const auto c = static_cast<unsigned char>(ch);
      if (c == '\n' || (c >= 0x20 && c < 0x7f)) continue;
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", c);
      error = "dialect setting '" + key + "' holds the byte " + hex +
              ", which is not printable ASCII: no controller may get it";
      return false;
    }
    std::size_t start = 0;
    while (start <= out.size()) {
      std::size_t end = out.find('\n', start);
      if (end == std::string::npos) end = out.size();
      const std::string line = out.substr(start, end - start);
      start = end + 1;
      if (moves_in_work_frame(line)) {
        error = "dialect setting '" + key + "' gives X or Z in the work frame ('" + line +
                "'): the program's own approach and retract keep clear of the part, a move "
                "here would not be checked against it (and a preset would shift the frame); "
                "park in machine coordinates (G53)";
        return false;
      }
    }
    return true;
  }
  // One of `choices`, as written.
  bool one_of(const std::string& key, const std::string& fallback,
              std::initializer_list<const char*> choices, std::string& out, std::string& error) {
    out = text(key, fallback);
    std::string listed;
    for (const char* c : choices) {
      if (out == c) return true;
      listed += (listed.empty() ? "" : ", ") + std::string(c);
    }
    error = "dialect setting '" + key + "' must be one of " + listed + ", not '" + out + "'";
    return false;
  }
  // The keys the plugin asked for, comma-separated (for messages).
  std::string known_keys() const {
    std::string out;
    for (const auto& [key, used] : used_) out += (out.empty() ? "" : ", ") + key;
    return out;
  }
  // The first key that was never asked for, or "".
  std::string unknown_key() const {
    for (const auto& [key, value] : values_)
      if (!used_.count(key)) return key;
    return {};
  }

 private:
  static std::string shortest(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", v);
    return buf;
  }
  // Whether `line` carries an X, Z, U or W word outside its comments and no G53.
  // A reference return through increments of 0 (Fanuc's G28 U0 W0) passes through no
  // point of the work frame.
  static bool moves_in_work_frame(const std::string& line) {
    bool moves = false, machine = false, reference = false, zero_increments = true;
    int depth = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char ch = line[i];
      if (ch == ';' && depth == 0) break;
      if (ch == '(' || ch == ')') {
        depth += ch == '(' ? 1 : (depth > 0 ? -1 : 0);
        continue;
      }
      if (depth > 0) continue;
      const char letter = ch >= 'a' && ch <= 'z' ? static_cast<char>(ch - 32) : ch;
      const auto numeric = [&](std::size_t k) {
        return k < line.size() && ((line[k] >= '0' && line[k] <= '9') || line[k] == '-' ||
                                   line[k] == '+' || line[k] == '.');
      };
      if (!numeric(i + 1)) continue;
      if (letter == 'X' || letter == 'Z' || letter == 'U' || letter == 'W') {
        moves = true;
        bool zero = letter == 'U' || letter == 'W';
        for (std::size_t j = i + 1; numeric(j); ++j) zero &= !(line[j] >= '1' && line[j] <= '9');
        zero_increments &= zero;
      }
      if (letter == 'G') {
        std::size_t j = i + 1;
        while (j < line.size() && line[j] == '0') ++j;
        const auto code = [&](const char* digits) {
          return line.compare(j, 2, digits) == 0 &&
                 (j + 2 >= line.size() ||
                  !((line[j + 2] >= '0' && line[j + 2] <= '9') || line[j + 2] == '.'));
        };
        machine |= code("53");
        reference |= code("28") || code("30");
      }
    }
    return moves && !machine && !(reference && zero_increments);
  }
  static std::string trim(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
  }
  std::map<std::string, std::string> values_;
  std::map<std::string, bool> used_;
};

}  // namespace freeturn::post
