#include "freeturn/post/nc_guard.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>

#include "freeturn/core/number_text.hpp"
#include "freeturn/io/nc_line.hpp"

namespace freeturn {
namespace {

// ASCII classes: every byte check_line classifies is printable ASCII by then, and the C
// library's (locale-dependent, one call a byte) would cost more than the rest of the guard.
constexpr bool ascii_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
constexpr char ascii_lower(char c) {
  return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c;
}
constexpr char ascii_upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 32) : c; }

std::string ascii_upper_text(std::string_view word) {
  std::string out(word);
  for (char& ch : out) ch = ascii_upper(ch);
  return out;
}

}  // namespace

NcGuard::NcGuard(const MachineDescription& machine) {
  std::fill(std::begin(max_velocity_), std::end(max_velocity_),
            std::numeric_limits<double>::infinity());
  for (const AxisSpec& s : machine.axes) {
    const char letter = axis_letter(s.axis)[0];
    max_velocity_[letter - 'A'] = s.max_velocity;
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
  // The most integer digits a number may have and still be inside on either side: 10ⁿ ≤
  // max (and the range holds 0) for positive numbers, −10ⁿ ≥ min for negative ones.
  for (Range& r : ranges_) {
    if (!r.checked || !(r.min <= 0 && r.max >= 0)) continue;
    for (int n = 0; n <= 15 && std::pow(10.0, n) <= r.max; ++n) r.digits_above = n;
    for (int n = 0; n <= 15 && -std::pow(10.0, n) >= r.min; ++n) r.digits_below = n;
  }
}

std::string NcGuard::check_record(const AxisRecord& record, long long block) const {
  const std::pair<char, double> values[] = {{'X', record.x}, {'Z', record.z}, {'C', record.c}, {'B', record.b}};
  // The usual answer first, without building a message (this runs for every block).
  bool fine = std::isfinite(record.time) && record.time >= 0;
  for (const auto& [letter, v] : values) {
    const Range& r = ranges_[letter - 'A'];
    fine = fine && std::isfinite(v) && !(letter != 'C' && r.checked && (v < r.min || v > r.max));
  }
  if (fine) return {};
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
  // A file's lines need not follow the last file's in the order they run: its angles are
  // not known from them.
  if (index != current_)
    for (RotaryAngle& a : rotary_) a.length = -1;
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
    ++f.lines;
    if (f.line.empty()) {
      check_line(bytes.substr(0, newline));  // a whole line in this piece: read in place
    } else {
      f.line.append(bytes.substr(0, newline));
      check_line(f.line);
      f.line.clear();
    }
    bytes.remove_prefix(newline + 1);
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
  // A child runs in its caller's modes and returns its own to it: one that left a mode
  // would move its caller's later words under it, which the caller's file does not show.
  for (std::size_t k = 1; k < files_.size(); ++k) {
    const int left = files_[k].modes.left(false);
    if (left < 0) continue;
    current_ = k;
    return refuse("the child returns to its caller under " + files_[k].modes.why(left) +
                  ", where the caller's words assume " + kNcModesAssumed);
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
  // Every byte must be printable text, comments included: a controller reads every byte of
  // a line. The place is found only on refusal.
  const NcLineBytes bytes = classify_nc_bytes(line);
  if (nc_line_too_long(line))
    return refuse("a line of " + std::to_string(line.size()) + " characters, longer than the " +
                  std::to_string(kMaxNcLineLength) +
                  " a controller reads: " + std::string(line.substr(0, 40)) + "…");
  if (bytes.unprintable) {
    for (std::size_t i = 0; i < line.size(); ++i) {
      const unsigned char byte = static_cast<unsigned char>(line[i]);
      if (nc_byte_unprintable(byte)) {
        char text[8];
        std::snprintf(text, sizeof text, "0x%02X", byte);
        return refuse("byte " + std::string(text) + " at column " + std::to_string(i + 1) +
                      " is not printable ASCII");
      }
    }
  }
  // The words outside comments: "( … )" and everything after ';' (io/nc_line.hpp).
  std::string_view code = line;
  if (bytes.comment_marks) {
    if (const NcCommentError error = strip_nc_comments(line, code_))
      return refuse(std::string(error.what) + " (column " + std::to_string(error.column) +
                    "): " + std::string(line));
    code = code_;
  }
  File& this_file = files_[current_];
  // Whether a line before this one had anything on it: asked of a file's first lines only.
  const bool first_content = this_file.blank_so_far;
  if (first_content && line.find_first_not_of(" \t\r") != std::string_view::npos)
    this_file.blank_so_far = false;
  // The tape's marks (io/nc_line.hpp). A '%' among a block's words is none (the word scan
  // below refuses it).
  if (const TapeMark mark = tape_mark(code); mark != TapeMark::kNone) {
    if (mark == TapeMark::kWordsAfter)
      return refuse("'%' with words after it on its line: " + std::string(line));
    if (!first_content && this_file.ended_at == 0) {
      this_file.ended_at = this_file.lines;
      this_file.end_word = "%";
    }
    return;
  }
  const char* const c = code.data();
  const std::size_t length = code.size();
  // Machine-coordinate moves (G53) and position presets (G10, G52, G92) are not in the work
  // frame the travel is given in: their numbers need only be finite. Such a word may follow
  // the axis words, so a word outside the travel is refused only once the whole line is
  // read. A reference return's (G28, G30) axis words are the point it passes through
  // first, in the work frame.
  bool words = false;
  // What the line asks of the modes its axis words assume (io/nc_line.hpp).
  bool machine_frame = false, reference_return = false, presets = false, calls_child = false;
  bool sets_position = false;   // G92: the axis words are where the axes now are
  unsigned axis_letters = 0;    // a bit per axis letter on the line, from 'A'
  bool axis_words_zero = true;  // every axis word reads 0
  char preset_letter = 0;  // the first axis word other than C (a preset moves that axis' frame)
  // The line's G codes are read as codes only where it holds more than one: two codes of
  // one RS-274 modal group contradict each other (G0 G1, G93 G94).
  std::string_view first_g;
  int g_count = 0;
  unsigned g_groups = 0;  // the modal groups of the line's G codes so far, a bit each
  const auto g_code_conflicts = [&](std::string_view number) {
    double value = 0;
    const int group = parse_plain_decimal(number, value) ? g_code_modal_group(value) : -1;
    if (!(group > 0 && group < 32)) return false;
    if (g_groups & (1u << group)) {
      refuse("two G codes of RS-274's " + std::string(g_code_modal_group_name(group)) +
             " group in one block, which a controller refuses: " + std::string(line));
      return true;
    }
    g_groups |= 1u << group;
    return false;
  };
  std::string_view feed_number;  // the line's F, for a feed per minute
  std::string_view end_word;
  std::string_view rotary_number[3];  // the line's A, B and C words' numbers (by axis_letters)
  char outside_letter = 0;
  std::string_view outside_number;
  double outside_value = 0;
  for (std::size_t i = 0; i < length; ++i) {
    const char lower = ascii_lower(c[i]);
    if (!ascii_letter(lower)) {
      if (c[i] == '%')
        return refuse("'%' inside a block, where it is not a word: " + std::string(line));
      continue;
    }
    if (i + 2 < length) {
      const char b = ascii_lower(c[i + 1]), d = ascii_lower(c[i + 2]);
      if ((lower == 'n' && b == 'a' && d == 'n') || (lower == 'i' && b == 'n' && d == 'f'))
        return refuse("a number that is not finite: " + std::string(line));
    }
    // The word's number: an optional sign, digits, one '.'. The scan counts the digits
    // before the point that are significant (a number with n of them is below 10ⁿ in
    // size); its value is computed only where that cannot settle the range.
    std::size_t j = i + 1;
    const bool negative = j < length && c[j] == '-';
    if (j < length && (c[j] == '-' || c[j] == '+')) ++j;
    const std::size_t digits = j;
    int integer_digits = 0, points = 0, digit_count = 0;
    double integer_part = 0;  // the digits before the point (exact up to 15 of them)
    bool nonzero = false;
    for (; j < length; ++j) {
      const char ch = c[j];
      if (ascii_digit(ch)) {
        ++digit_count;
        nonzero |= ch != '0';
        integer_digits += (points == 0) & ((integer_digits != 0) | (ch != '0'));
        if (points == 0) integer_part = 10 * integer_part + (ch - '0');
      } else if (ch == '.') {
        ++points;
      } else {
        break;
      }
    }
    if (j == digits) {
      // A keyword's letter, unless it stands alone: then it is a word whose number is
      // missing or is not a number ("F" then garbage).
      const bool alone = (i == 0 || !ascii_letter(c[i - 1])) &&
                         (j >= length || !ascii_letter(c[j]));
      if (alone && std::string_view("xzcbf").find(lower) != std::string_view::npos)
        return refuse(std::string(1, ascii_upper(lower)) +
                      " without a number after it: " + std::string(line));
      continue;
    }
    words = true;
    const char letter = ascii_upper(lower);
    std::string_view number(c + i + 1, j - i - 1);
    if (!number.empty() && number.front() == '+') number.remove_prefix(1);
    if (points > 1 || digit_count == 0)
      return refuse(std::string(1, letter) + std::string(number) + " is not a number");
    if (lower == 'g') {
      if (g_count++ == 0)
        first_g = number;
      else if ((g_count == 2 && g_code_conflicts(first_g)) || g_code_conflicts(number))
        return;
      // The code's value: one or two digits (G1, G01, G93: every block of some dialects)
      // without the general parse.
      double g = 0;
      if (number.size() <= 2 && ascii_digit(number[0]) && ascii_digit(number.back()))
        for (const char ch : number) g = 10 * g + (ch - '0');
      else if (!parse_plain_decimal(number, g))
        return refuse("G" + std::string(number) + " is not a number");
      machine_frame |= g == 53;
      reference_return |= g == 28 || g == 30;
      presets |= g_code_presets_frame(g);
      sets_position |= g == 92;
      File& f = files_[current_];
      f.modes.apply(g, std::string_view(c + i, j - i), f.lines);
      if (g == 0 || g == 1) f.rapid = g == 0;
      if (g == 93 || g == 94) f.per_minute = g == 94;
    } else if (lower == 'm' && points == 0) {
      std::string_view code = number;
      while (code.size() > 1 && code.front() == '0') code.remove_prefix(1);
      if (code == "2" || code == "30" || code == "99") end_word = std::string_view(c + i, j - i);
      calls_child |= code == "98";
    } else if (nc_axis_letter(lower)) {
      axis_letters |= 1u << (lower - 'a');
      if (lower <= 'c') rotary_number[lower - 'a'] = number;
      axis_words_zero &= !nonzero;
      if (preset_letter == 0 && lower != 'c') preset_letter = letter;
    }
    // F is a feed, or a block's time or its inverse: none of them can be 0 in any mode (a
    // feed of 0 stalls or alarms the machine, an inverse time of 0 has no block time). A
    // job's tiny feed, or a long block, can round to it at the word's decimals.
    // Nor negative: no mode has a negative feed or time.
    if (lower == 'f') feed_number = number;
    if (lower == 'f' && (!nonzero || negative))
      return refuse(std::string(1, letter) + std::string(number) +
                    (nonzero ? " is negative: no feed or block time is"
                             : " is 0: a feed or block time the controller cannot run"));
    // Digits and at most one point, fewer than 309 before it: a finite number.
    const Range& r = ranges_[letter - 'A'];
    if (!r.checked && integer_digits < 300) {
      i = j - 1;
      continue;
    }
    if (r.checked && integer_digits <= (negative ? r.digits_below : r.digits_above)) {
      i = j - 1;  // inside: |v| < 10ⁿ, within the range on its sign's side
      continue;
    }
    // Inside where the whole interval its integer part allows is: [n, n + 1) for a
    // positive number, (−n − 1, −n] for a negative one (C's 100 to 359 on a wrapped C).
    if (r.checked && integer_digits <= 15 &&
        (negative ? -(integer_part + 1) >= r.min && -integer_part <= r.max
                  : integer_part >= r.min && integer_part + 1 <= r.max)) {
      i = j - 1;
      continue;
    }
    double v = 0;
    if (!parse_plain_decimal(number, v))
      return refuse(std::string(1, letter) + std::string(number) + " is not a number");
    if (outside_letter == 0 && r.checked && (v < r.min || v > r.max)) {
      outside_letter = letter;
      outside_number = number;
      outside_value = v;
    }
    i = j - 1;
  }
  const bool outside_frame = machine_frame || presets;
  File& file = files_[current_];
  if (presets && preset_letter != 0)
    return refuse(std::string(1, preset_letter) +
                  " in a preset (G10, G52, G92) moves the frame the program's positions are "
                  "given in (a preset of C alone sets the spindle's zero): " +
                  std::string(line));
  if (axis_letters != 0 || calls_child) {
    const int left = file.modes.left(outside_frame || (reference_return && axis_words_zero));
    if (left >= 0)
      return refuse(std::string(calls_child ? "a call of a child program" : "an axis word") +
                    " under " + file.modes.why(left) + ", where the program's words assume " +
                    kNcModesAssumed + ": " + std::string(line));
  }
  if (!feed_number.empty()) {
    file.feed.assign(feed_number);
    file.feed_value = std::numeric_limits<double>::quiet_NaN();  // read when first asked
  }
  // A feed per minute is the speed along the move: no linear axis goes faster than it, and
  // a rotary axis turning alone goes at it (°/min). A rotary axis turning with linear ones
  // takes the linear move's time (RS-274: the feed times the linear axes), so its speed is
  // its turn over the linear length: at F3000 (50 mm/s) a move of 1 µm beside a turn of 2°
  // asks 2° in 20 µs.
  // The lines do not settle that length (the program need not say where X was), so no such
  // move is written: the angle must be the last one written on this file.
  constexpr unsigned kRotary = 1u << ('a' - 'a') | 1u << ('b' - 'a') | 1u << ('c' - 'a');
  const bool feed_move =
      axis_letters != 0 && file.per_minute && !file.rapid && !file.feed.empty() && !outside_frame;
  if (feed_move && (axis_letters & kRotary) != 0 && (axis_letters & ~kRotary) != 0) {
    for (unsigned rest = axis_letters & kRotary; rest != 0; rest &= rest - 1) {
      const int k = std::countr_zero(rest);
      const std::string_view number = rotary_number[k];
      const RotaryAngle& last = rotary_[k];
      const std::string_view before(last.text, static_cast<std::size_t>(std::max(last.length, 0)));
      double now = 0, then = 0;
      if (last.length >= 0 &&
          (number == before ||
           (parse_plain_decimal(number, now) && parse_plain_decimal(before, then) && now == then)))
        continue;
      const char letter = static_cast<char>('A' + k);
      return refuse(std::string(1, letter) + std::string(number) + " turns " +
                    (last.length < 0 ? "from an angle no earlier line of the file gives"
                                     : "from " + std::string(1, letter) + std::string(before)) +
                    " together with a linear axis in a feed per minute (G94): its speed would "
                    "follow from the linear move's length, which the program does not settle; "
                    "turn it on a line of its own: " +
                    std::string(line));
    }
  }
  for (unsigned rest = axis_letters & kRotary; rest != 0; rest &= rest - 1) {
    const int k = std::countr_zero(rest);
    const std::string_view number = rotary_number[k];
    RotaryAngle& last = rotary_[k];
    // Outside the work frame, or a preset other than G92's "the axis is here", the angle
    // in the work frame is not known.
    const bool known = !machine_frame && !reference_return && (!presets || sets_position) &&
                       number.size() <= sizeof last.text;
    last.length = known ? static_cast<int>(number.size()) : -1;
    if (known) std::memcpy(last.text, number.data(), number.size());
  }
  if (feed_move) {
    const bool linear_words = (axis_letters & ~kRotary) != 0;
    const unsigned judged = linear_words ? axis_letters & ~kRotary : axis_letters;
    char slowest = 0;  // the judged axis of the least velocity limit
    for (unsigned rest = judged; rest != 0; rest &= rest - 1) {
      const int k = std::countr_zero(rest);
      if (slowest == 0 || max_velocity_[k] < max_velocity_[slowest - 'A'])
        slowest = static_cast<char>('A' + k);
    }
    const double limit = max_velocity_[slowest - 'A'];
    if (std::isnan(file.feed_value) && !parse_plain_decimal(file.feed, file.feed_value))
      file.feed_value = 0;
    const double feed = file.feed_value;
    if (limit < std::numeric_limits<double>::infinity() && feed / 60 > limit * (1 + 1e-12)) {
      crossed_ = {slowest, true, true};
      return refuse("F" + file.feed + " a minute (G94) moves " + std::string(1, slowest) + " at " +
                    shortest_text(feed / 60) + (linear_words ? " mm/s" : " deg/s") +
                    ", beyond its max_velocity " + shortest_text(limit) +
                    " in the machine file: " + std::string(line));
    }
  }
  if (words && file.ended_at > 0)
    return refuse("words after the program's end (" + file.end_word + " on line " +
                  std::to_string(file.ended_at) +
                  "), which the controller never runs: " + std::string(line));
  if (!end_word.empty()) {
    file.ended_at = file.lines;
    file.end_word = ascii_upper_text(end_word);
  }
  if (outside_letter != 0 && !outside_frame) {
    const Range& r = ranges_[outside_letter - 'A'];
    crossed_ = {outside_letter, outside_value > r.max};
    return refuse(std::string(1, outside_letter) + std::string(outside_number) +
                  " is outside the machine's range [" + shortest_text(r.min) + ", " +
                  shortest_text(r.max) + "]");
  }
}

}  // namespace freeturn
