#include "freeturn/io/nc_line.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace freeturn {

namespace {

// One byte's classes, as NcLineBytes says.
void classify_nc_byte(unsigned char byte, NcLineBytes& classes) {
  classes.unprintable |= nc_byte_unprintable(byte);
  classes.comment_marks |= byte == '(' || byte == ')' || byte == ';';
}

}  // namespace

NcLineBytes classify_nc_bytes(std::string_view line) {
  constexpr std::uint64_t kOnes = 0x0101010101010101ull, kHighs = 0x8080808080808080ull;
  // Whether any byte of w is below n (1 ≤ n ≤ 128), for a word with no byte of 128 or more:
  // a byte b < n borrows and leaves its high bit set, where ~w's is set too; a borrow into
  // the byte above can flag that one as well, but only after a byte that is below n. The
  // word's answer is exact (Anderson, "Bit Twiddling Hacks": hasless).
  const auto has_below = [](std::uint64_t w, std::uint64_t n) {
    return ((w - kOnes * n) & ~w & kHighs) != 0;
  };
  NcLineBytes classes;
  // Any byte of 128 or more, below ' ', DEL (0x7F: zero after the xor) or a comment's mark
  // among the 8 at p: those are read one by one (tab and CR are below ' ').
  const auto classify_word = [&](const char* p, std::uint64_t w) {
    const bool plain = (w & kHighs) == 0 && !has_below(w, 0x20) &&
                       !has_below(w ^ (kOnes * 0x7F), 1) && !has_below(w ^ (kOnes * '('), 1) &&
                       !has_below(w ^ (kOnes * ')'), 1) && !has_below(w ^ (kOnes * ';'), 1);
    if (!plain)
      for (int k = 0; k < 8; ++k) classify_nc_byte(static_cast<unsigned char>(p[k]), classes);
  };
  const char* const data = line.data();
  const std::size_t size = line.size();
  if (size < 8) {
    for (std::size_t k = 0; k < size; ++k)
      classify_nc_byte(static_cast<unsigned char>(data[k]), classes);
    return classes;
  }
  std::uint64_t w;
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::memcpy(&w, data + i, 8);
    classify_word(data + i, w);
  }
  // The last 8 bytes, some of them read already (the answer is an or over the bytes).
  if (i < size) {
    std::memcpy(&w, data + size - 8, 8);
    classify_word(data + size - 8, w);
  }
  return classes;
}

std::size_t nc_comment_close(std::string_view line, std::size_t open, NcCommentError& error) {
  for (std::size_t k = open + 1; k < line.size(); ++k) {
    if (line[k] == ')') return k;
    if (line[k] == '(') {
      error = {k + 1, "'(' inside a comment: controllers do not nest comments"};
      return std::string_view::npos;
    }
  }
  error = {open + 1, "a comment '(' without ')' on its line: a controller stops there"};
  return std::string_view::npos;
}

NcCommentError nc_stray_comment_close(std::size_t at) {
  return {at + 1, "')' outside a comment"};
}

NcCommentError strip_nc_comments(std::string_view line, std::string& code) {
  code.clear();
  NcCommentError error;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char ch = line[k];
    if (ch == ';') break;
    if (ch == ')') return nc_stray_comment_close(k);
    if (ch != '(') {
      code += ch;
      continue;
    }
    k = nc_comment_close(line, k, error);
    if (error) return error;
  }
  return error;
}

namespace {

// LinuxCNC's G-code table: each code (in tenths: G38.2 is 382) with its modal group.
struct CodeGroup {
  int tenths;
  int group;
};
// clang-format off
constexpr CodeGroup kCodeGroups[] = {
    // 1, motion
    {0, 1}, {10, 1}, {20, 1}, {30, 1}, {330, 1}, {382, 1}, {383, 1}, {384, 1}, {385, 1},
    {730, 1}, {760, 1}, {800, 1}, {810, 1}, {820, 1}, {830, 1}, {840, 1}, {850, 1}, {860, 1},
    {870, 1}, {880, 1}, {890, 1},
    // 2, plane
    {170, 2}, {180, 2}, {190, 2}, {171, 2}, {181, 2}, {191, 2},
    // 3, distance mode
    {900, 3}, {910, 3},
    // 4, arc distance mode
    {901, 4}, {911, 4},
    // 5, feed-rate mode
    {930, 5}, {940, 5}, {950, 5},
    // 6, units
    {200, 6}, {210, 6},
    // 7, cutter compensation
    {400, 7}, {410, 7}, {420, 7}, {411, 7}, {421, 7},
    // 8, tool length offset
    {430, 8}, {431, 8}, {490, 8},
    // 10, canned-cycle return
    {980, 10}, {990, 10},
    // 12, coordinate system
    {540, 12}, {550, 12}, {560, 12}, {570, 12}, {580, 12}, {590, 12}, {591, 12}, {592, 12},
    {593, 12},
    // 13, path control
    {610, 13}, {611, 13}, {640, 13},
    // 14, spindle-speed mode
    {960, 14}, {970, 14},
    // 15, diameter or radius mode
    {70, 15}, {80, 15},
};
// clang-format on
// The groups' names, by number (none for 0, 9 and 11).
constexpr const char* kGroupNames[16] = {nullptr,
                                         "motion",
                                         "plane",
                                         "distance mode",
                                         "arc distance mode",
                                         "feed-rate mode",
                                         "units",
                                         "cutter compensation",
                                         "tool length offset",
                                         nullptr,
                                         "canned-cycle return",
                                         nullptr,
                                         "coordinate system",
                                         "path control",
                                         "spindle-speed mode",
                                         "diameter or radius mode"};

}  // namespace

int g_code_modal_group(double value) {
  // G codes are named to a tenth (G38.2, G64.1); another value is no code of the table.
  const double tenths = value * 10;
  if (!(std::abs(tenths - std::round(tenths)) < 1e-9) || !(std::abs(tenths) < 1e4)) return -1;
  const long code = std::lround(tenths);
  for (const CodeGroup& c : kCodeGroups)
    if (c.tenths == code) return c.group;
  return -1;
}

const char* g_code_modal_group_name(int group) {
  return group >= 0 && group < 16 && kGroupNames[group] ? kGroupNames[group] : "no";
}

NcModeChange g_code_mode_change(double value) {
  const double tenths = value * 10;
  if (!(std::abs(tenths - std::round(tenths)) < 1e-9) || !(std::abs(tenths) < 1e4)) return {};
  using M = NcMode;
  switch (std::lround(tenths)) {
    case 900:
      return {int(M::kAbsolute), true, ""};
    case 910:
      return {int(M::kAbsolute), false, "incremental distances"};
    case 210:
    case 710:
      return {int(M::kMillimetres), true, ""};
    case 200:
    case 700:
      return {int(M::kMillimetres), false, "inches"};
    case 400:
      return {int(M::kNoCompensation), true, ""};
    case 410:
    case 420:
    case 411:
    case 421:
      return {int(M::kNoCompensation), false, "cutter-radius compensation"};
    case 80:
      return {int(M::kRadius), true, ""};
    case 70:
      return {int(M::kRadius), false, "diameter mode"};
    case 0:
    case 10:
      return {int(M::kStraightMotion), true, ""};
    case 930:
    case 940:
      return {int(M::kFeedByTime), true, ""};
    case 950:
      return {int(M::kFeedByTime), false, "feed per revolution"};
    default:
      break;
  }
  if (g_code_modal_group(value) == 1)
    return {int(M::kStraightMotion), false, "a motion mode that is no straight move"};
  return {};
}

std::string NcModeState::why(int mode) const {
  const Left& left = left_[mode];
  return left.code + " (" + left.what + ", line " + std::to_string(left.at) + ")";
}

}  // namespace freeturn
