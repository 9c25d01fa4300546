#pragma once
// What a controller reads of one NC line: the comments it skips, the tape's marks and the
// G codes' modal groups. One statement of each, shared by the reader (parse_nc, ncdiff)
// and the guard that reads every written line back (post/nc_guard.hpp).

#include <cstddef>
#include <string>
#include <string_view>

namespace freeturn {

// The longest line a controller reads: LinuxCNC's buffer holds 255 characters and stops on
// a longer line ("command too long"). A trailing CR is not counted.
inline constexpr std::size_t kMaxNcLineLength = 255;
inline bool nc_line_too_long(std::string_view line) {
  return line.size() > kMaxNcLineLength &&
         !(line.size() == kMaxNcLineLength + 1 && line.back() == '\r');
}

// A byte a controller must not be sent: not printable text (below ' ' or above '~'), tab
// and CR aside.
inline bool nc_byte_unprintable(unsigned char byte) {
  return (byte < 0x20 && byte != '\t' && byte != '\r') || byte > 0x7E;
}

// What the guard asks first of every byte of a line it reads back: whether any byte is
// unprintable (nc_byte_unprintable), and whether any is a comment's mark ('(', ')' or ';'),
// when the comments must be read.
struct NcLineBytes {
  bool unprintable = false;
  bool comment_marks = false;
};
// Eight bytes a step (a word's bytes compared at once), each flagged word's bytes again one
// by one: the same answer as a loop over the bytes, at 0.45 times its instructions on a
// program's lines (docs/path.md, "Posting").
NcLineBytes classify_nc_bytes(std::string_view line);

// A line's comments as RS-274 readers take them (LinuxCNC's, Fanuc's): "( … )" up to the
// first ')', and everything from a ';' outside one to the line's end. A controller stops on
// a '(' inside a comment (LinuxCNC: "nested comment found"), on a comment still open at
// the line's end ("unclosed comment found": the words after it would be lost) and on a
// ')' outside a comment.
struct NcCommentError {
  std::size_t column = 0;  // 1-based, in the line; 0: the line keeps the rule
  const char* what = "";
  explicit operator bool() const { return column != 0; }
};

// The index of the ')' that closes the comment opened at line[open] (a '('), or npos with
// `error` set.
std::size_t nc_comment_close(std::string_view line, std::size_t open, NcCommentError& error);

// The error of a ')' at line[at], outside any comment.
NcCommentError nc_stray_comment_close(std::size_t at);

// `line` without its comments, into `code` (cleared first), and the line's first breach of
// the rule above (then `code` holds what came before it).
NcCommentError strip_nc_comments(std::string_view line, std::string& code);

// The tape's marks (RS-274, LinuxCNC, Fanuc): a line of '%' alone (spaces and comments
// aside) starts the program when it is the file's first line with anything on it, and ends
// it anywhere later; the controller reads nothing after the end. A '%' with words after it
// on its line is no mark and no word, and a '%' among a block's words is none either: both
// are the reader's and the guard's to refuse.
enum class TapeMark {
  kNone,        // the line's code does not start with '%'
  kMark,        // '%' alone
  kWordsAfter,  // '%' first, with words after it
};
// `code`: a line without its comments (strip_nc_comments). Inline: the guard asks it of
// every line it reads back.
inline TapeMark tape_mark(std::string_view code) {
  const std::size_t first = code.find_first_not_of(" \t\r");
  if (first == std::string_view::npos || code[first] != '%') return TapeMark::kNone;
  return code.find_last_not_of(" \t\r") == first ? TapeMark::kMark : TapeMark::kWordsAfter;
}

// The RS-274 modal group of the G code `value` (LinuxCNC's table): 1 motion (G0 G1 G2 G3
// G33 G38.x G73 G76 G80–G89), 2 plane, 3 distance, 4 arc distance, 5 feed-rate mode
// (G93 G94 G95), 6 units, 7 cutter compensation, 8 tool length offset, 10 canned-cycle
// return, 12 coordinate system, 13 path control, 14 spindle-speed mode, 15 lathe diameter
// or radius; −1 for a code of no group, or one the table does not know (a dialect's own).
// Two codes of one group in a block contradict each other, and a controller refuses it.
int g_code_modal_group(double value);
// The group's name ("motion", "feed-rate mode").
const char* g_code_modal_group_name(int group);

// The modes a program's axis words assume as freeturn writes them, and the G codes that
// keep or leave each (LinuxCNC's reading, with a Moore's units):
// - absolute distances: G90 keeps it, G91 leaves it (each word an increment);
// - millimetres: G21 and a Moore's G71 keep it, G20 and a Moore's G70 leave it (inches);
// - no cutter compensation: G40 keeps it, G41, G42, G41.1, G42.1 leave it (the axes carry
//   the nose already, and the controller would offset them again);
// - radius mode: G8 keeps it, G7 leaves it (X read as a diameter);
// - straight motion: G0 and G1 keep it, any other code of the motion group leaves it (G80
//   too): an arc or a canned cycle reads the next block's axis words as its own;
// - feeds by time: G93 (inverse time) and G94 (per minute) keep it, G95 leaves it (per
//   revolution: every F, the modal one too, read as millimetres a turn).
enum class NcMode {
  kAbsolute,
  kMillimetres,
  kNoCompensation,
  kRadius,
  kStraightMotion,
  kFeedByTime
};
inline constexpr int kNcModeCount = 6;
// The modes together, for messages.
inline constexpr const char* kNcModesAssumed =
    "absolute millimetres in radius mode, no cutter compensation, straight moves and feeds by "
    "time (G93 or G94)";
struct NcModeChange {
  int mode = -1;          // an NcMode, or −1: the code touches none of them
  bool keeps = true;      // sets the mode (true) or leaves it (false)
  const char* what = "";  // what leaving it means ("incremental distances")
};
NcModeChange g_code_mode_change(double value);

// The modes above as a program's lines set them, read in the order a controller reads them.
class NcModeState {
 public:
  // G `value`, written as `code` ("G91"), on line `line`.
  void apply(double value, std::string_view code, long long line) {
    if (value == 1 || value == 0) {  // every block of some dialects: no table
      left_[static_cast<int>(NcMode::kStraightMotion)].at = 0;
      left_mask_ &= ~(1u << static_cast<int>(NcMode::kStraightMotion));
      return;
    }
    const NcModeChange change = g_code_mode_change(value);
    if (change.mode < 0) return;
    Left& left = left_[change.mode];
    left.at = change.keeps ? 0 : line;
    if (change.keeps) {
      left_mask_ &= ~(1u << change.mode);
    } else {
      left_mask_ |= 1u << change.mode;
      left.code.assign(code);
      left.what = change.what;
    }
  }
  // The first mode an axis word may not move under (−1: none). `any_distance`: the words
  // are machine coordinates (G53, absolute in every distance mode), or a reference
  // return's increments of 0 (G91 G28 X0 Z0 passes through no other point).
  int left(bool any_distance) const {
    if (left_mask_ == 0) return -1;
    for (int m = 0; m < kNcModeCount; ++m)
      if (left_[m].at != 0 && !(any_distance && m == static_cast<int>(NcMode::kAbsolute))) return m;
    return -1;
  }
  // "G91 (incremental distances, line 3)".
  std::string why(int mode) const;

 private:
  struct Left {
    long long at = 0;  // the line whose code left the mode (0: kept, or never left)
    std::string code;  // that code as written
    const char* what = "";
  };
  Left left_[kNcModeCount];
  unsigned left_mask_ = 0;  // a bit per mode left
};

// Whether `letter` (either case) is an axis word of RS-274's: X Y Z A B C U V W.
inline bool nc_axis_letter(char letter) {
  const unsigned k = static_cast<unsigned>((letter | 0x20) - 'a');
  constexpr unsigned kAxes = 1u << ('x' - 'a') | 1u << ('y' - 'a') | 1u << ('z' - 'a') |
                             1u << ('a' - 'a') | 1u << ('b' - 'a') | 1u << ('c' - 'a') |
                             1u << ('u' - 'a') | 1u << ('v' - 'a') | 1u << ('w' - 'a');
  return k < 26 && ((kAxes >> k) & 1u);
}

// Whether G `value` presets a coordinate frame from its axis words (G10, G52, G92): the
// positions written after it would then lie elsewhere on the machine.
inline bool g_code_presets_frame(double value) {
  return value == 10 || value == 52 || value == 92;
}

}  // namespace freeturn
