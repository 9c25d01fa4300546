#pragma once
// What a controller reads of one NC line before its words: the comments it skips and the
// tape's marks. One statement of each, shared by the reader (parse_nc) and the guard that
// reads every written line back (post/nc_guard.hpp).

#include <string>
#include <string_view>

namespace freeturn {

// `line` without its comments, into `code` (cleared first): "( … )", nested, and
// everything from a ';' outside one to the line's end.
void strip_nc_comments(std::string_view line, std::string& code);

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
// `code`: a line without its comments (strip_nc_comments).
TapeMark tape_mark(std::string_view code);

}  // namespace freeturn
