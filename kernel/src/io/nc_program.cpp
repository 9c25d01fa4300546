#include "freeturn/io/nc_program.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/input_file.hpp"
#include "freeturn/io/nc_line.hpp"

namespace freeturn {

namespace {

// Words a block may give once: an axis's target, or its feed (a block time under G93).
bool is_unique_word(char letter) {
  return std::string("XYZABCUVWF").find(letter) != std::string::npos;
}

// M02 or M30: the program ends. M99: a child returns (the main program ends there too: a
// controller that would run it again would cut the same path again).
bool has_code(const NcBlock& b, char letter, std::initializer_list<double> values) {
  for (const NcWord& w : b.words)
    if (w.numeric && w.letter == letter)
      for (double v : values)
        if (w.value == v) return true;
  return false;
}

}  // namespace

std::vector<NcBlock> parse_nc(const std::string& text, const std::string& file) {
  std::vector<NcBlock> blocks;
  int line = 0;
  std::size_t start = 0;
  bool seen_content = false;  // a line with anything on it: a '%' after it ends the tape
  std::string code;           // the line without its comments
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string l = text.substr(start, end - start);
    start = end + 1;
    ++line;
    if (nc_line_too_long(l))
      throw InputError(SourceLocation{file, line, static_cast<int>(kMaxNcLineLength) + 1},
                       "a line of " + std::to_string(l.size()) + " characters, longer than the " +
                           std::to_string(kMaxNcLineLength) + " a controller reads");
    const std::size_t first = l.find_first_not_of(" \t\r");
    // A tape mark needs a '%': the comments are stripped for the test only then.
    TapeMark mark = TapeMark::kNone;
    if (l.find('%') != std::string::npos) {
      if (const NcCommentError error = strip_nc_comments(l, code))
        throw InputError(SourceLocation{file, line, static_cast<int>(error.column)}, error.what);
      mark = tape_mark(code);
    }
    if (mark == TapeMark::kMark) {
      if (seen_content) break;  // the tape's end
      seen_content = true;      // its start
      continue;
    } else if (mark == TapeMark::kWordsAfter) {
      const std::size_t at = l[first] == '%' ? first : l.find('%');
      throw InputError(SourceLocation{file, line, static_cast<int>(at) + 1},
                       "'%' with words after it on its line: a tape mark stands alone");
    }
    if (first != std::string::npos) seen_content = true;
    NcBlock block;
    block.line = line;
    std::size_t i = 0;
    const auto fail = [&](const std::string& what) {
      throw InputError(SourceLocation{file, line, static_cast<int>(i) + 1}, what);
    };
    // Where each axis and F word of this block was first given (0: not yet).
    int first_column[26] = {0};
    // The G code of each RS-274 modal group this block states, and where (0: none yet).
    int group_column[16] = {0};
    std::size_t group_length[16] = {0};  // that code's length as written
    while (i < l.size()) {
      const char ch = l[i];
      if (ch == ' ' || ch == '\t' || ch == '\r') {
        ++i;
      } else if (ch == '(') {
        NcCommentError error;
        const std::size_t close = nc_comment_close(l, i, error);
        if (error) {
          i = error.column - 1;
          fail(error.what);
        }
        i = close + 1;
      } else if (ch == ')') {
        fail(nc_stray_comment_close(i).what);
      } else if (ch == ';') {
        break;
      } else if (ch == '/') {
        ++i;
      } else if (ch == '%') {
        fail("'%' inside a block, where it is not a word");
      } else if (std::isalpha(static_cast<unsigned char>(ch)) || ch == '#' || ch == '[') {
        NcWord w;
        w.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
        w.column = static_cast<int>(i) + 1;
        std::size_t j = i + 1;
        // A number: sign, digits, point.
        const std::size_t number_start = j;
        if (j < l.size() && (l[j] == '-' || l[j] == '+')) ++j;
        while (j < l.size() && (std::isdigit(static_cast<unsigned char>(l[j])) || l[j] == '.')) ++j;
        // "X1e5" is no X1 followed by a word E5: an exponent no controller reads.
        if (j > number_start && j + 1 < l.size() && (l[j] == 'e' || l[j] == 'E')) {
          std::size_t k = j + 1;
          if (k < l.size() && (l[k] == '-' || l[k] == '+')) ++k;
          if (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k]))) {
            while (k < l.size() && std::isdigit(static_cast<unsigned char>(l[k]))) ++k;
            i = j;
            fail("'" + l.substr(number_start - 1, k - number_start + 1) +
                 "' is in exponent notation, which NC controllers do not read as one number");
          }
        }
        const std::string number = l.substr(number_start, j - number_start);
        if (ch != '#' && ch != '[' && !number.empty() && number != "-" && number != "+" &&
            number != ".") {
          if (!parse_finite(number, w.value))
            fail("'" + std::string(1, w.letter) + number + "' is not a number");
          w.text = std::string(1, w.letter) + number;
          // M98(child.nc): the parentheses are the call's argument, not a comment.
          if (w.letter == 'M' && w.value == 98 && j < l.size() && l[j] == '(') {
            const std::size_t close = l.find(')', j);
            if (close == std::string::npos) fail("M98( without ')'");
            w.numeric = false;
            w.text = "M98" + l.substr(j, close + 1 - j);
            j = close + 1;
          }
          if (w.letter == 'G' && w.numeric) {
            const int group = g_code_modal_group(w.value);
            if (group > 0 && group < 16) {
              if (group_column[group] != 0)
                fail(l.substr(i, j - i) + " after " +
                     l.substr(static_cast<std::size_t>(group_column[group] - 1),
                              group_length[group]) +
                     " (column " + std::to_string(group_column[group]) +
                     ") in one block: both are codes of RS-274's " +
                     g_code_modal_group_name(group) + " group, and a controller refuses the block");
              group_column[group] = w.column;
              group_length[group] = j - i;
            }
          }
          if (is_unique_word(w.letter)) {
            int& first = first_column[w.letter - 'A'];
            if (first != 0)
              fail(std::string(1, w.letter) + " is given twice in one block (first at column " +
                   std::to_string(first) + "): a controller stops there or takes one of them");
            first = w.column;
          }
          block.words.push_back(w);
          i = j;
          continue;
        }
        // Macro keywords (Moore/Fanuc style: WHILE[…]DO1, IF[…]GOTO31, END1).
        if (std::isalpha(static_cast<unsigned char>(ch))) {
          std::size_t e = i;
          while (e < l.size() && std::isalpha(static_cast<unsigned char>(l[e]))) ++e;
          std::string keyword = l.substr(i, e - i);
          for (char& c : keyword) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
          static const std::set<std::string> kKeywords = {"WHILE", "DO", "END", "IF", "GOTO", "THEN"};
          if (!kKeywords.count(keyword)) {
            std::string what = "'";
            what += l.substr(i, e - i);
            what += "' is not an NC word (a letter and a number)";
            fail(what);
          }
        }
        // Not a plain word: macro syntax or a keyword; keep the rest of the token.
        std::size_t k = i;
        int depth = 0;
        while (k < l.size() && (depth > 0 || (l[k] != ' ' && l[k] != '\t' && l[k] != '\r'))) {
          if (l[k] == '(' || l[k] == '[') ++depth;
          if (l[k] == ')' || l[k] == ']') --depth;
          ++k;
        }
        if (std::isalpha(static_cast<unsigned char>(ch)) && k == i + 1)
          fail(std::string("the letter ") + ch + " has no value");
        w.numeric = false;
        w.text = l.substr(i, k - i);
        block.words.push_back(w);
        i = k;
      } else {
        fail(std::string("'") + ch + "' is not NC: expected a letter and a number");
      }
    }
    if (!block.words.empty()) blocks.push_back(std::move(block));
  }
  return blocks;
}

std::string read_nc_text(const std::string& path) {
  require_regular_file(path, "an NC program");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{path, 0, 0}, "cannot open the NC program");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<NcBlock> read_nc_program(const std::string& path, std::vector<std::string>* files) {
  std::vector<std::string> read_files;
  const auto read = [&read_files](const std::string& file) {
    std::vector<NcBlock> blocks = parse_nc(read_nc_text(file), file);
    for (NcBlock& b : blocks) b.file = static_cast<int>(read_files.size());
    read_files.push_back(file);
    return blocks;
  };
  std::vector<NcBlock> blocks;
  const auto done = [&] {
    if (files) *files = std::move(read_files);
    return std::move(blocks);
  };
  for (NcBlock& b : read(path)) {
    if (has_code(b, 'M', {2, 30, 99})) {
      blocks.push_back(std::move(b));
      return done();
    }
    std::string child;
    SourceLocation call;
    for (const NcWord& w : b.words)
      if (!w.numeric && w.text.rfind("M98(", 0) == 0 && w.text.back() == ')') {
        child = w.text.substr(4, w.text.size() - 5);
        call = SourceLocation{read_files[static_cast<std::size_t>(b.file)], b.line, w.column};
        // The controller finds a child beside its caller, by its name: a path here (to
        // /etc/passwd, or up the tree with "..") is no program a post writes, and would
        // read, and quote, any file.
        if (child.find('/') != std::string::npos || child.find('\\') != std::string::npos ||
            child == "." || child == "..")
          throw InputError(call,
                           "M98 calls '" + child +
                               "': a child program is read beside its caller, by its file name, "
                               "not a path");
      }
    if (child.empty()) {
      blocks.push_back(std::move(b));
      continue;
    }
    const std::string child_path = (std::filesystem::path(path).parent_path() / child).string();
    std::error_code ec;
    if (!std::filesystem::exists(child_path, ec))
      throw InputError(call, "M98 calls '" + child + "', which is not beside " +
                                 std::filesystem::path(path).filename().string());
    for (NcBlock& cb : read(child_path)) {
      for (const NcWord& w : cb.words)
        if (!w.numeric && w.text.rfind("M98(", 0) == 0)
          throw InputError(SourceLocation{child_path, cb.line, w.column},
                           "a child program calls another (one level of M98 is read)");
      const bool ends = has_code(cb, 'M', {2, 30});
      const bool returns = has_code(cb, 'M', {99});
      blocks.push_back(std::move(cb));
      if (ends) return done();
      if (returns) break;
    }
  }
  return done();
}

}  // namespace freeturn
