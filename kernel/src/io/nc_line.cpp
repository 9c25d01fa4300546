#include "freeturn/io/nc_line.hpp"

namespace freeturn {

void strip_nc_comments(std::string_view line, std::string& code) {
  code.clear();
  int depth = 0;
  for (const char ch : line) {
    if (ch == ';' && depth == 0) break;
    if (ch == '(') ++depth;
    else if (ch == ')' && depth > 0) --depth;
    else if (depth == 0) code += ch;
  }
}

TapeMark tape_mark(std::string_view code) {
  const std::size_t first = code.find_first_not_of(" \t\r");
  if (first == std::string_view::npos || code[first] != '%') return TapeMark::kNone;
  return code.find_last_not_of(" \t\r") == first ? TapeMark::kMark : TapeMark::kWordsAfter;
}

}  // namespace freeturn
