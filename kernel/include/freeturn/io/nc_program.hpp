#pragma once
// NC programs read back as words (ISO 6983 style: a letter and a number), for ncdiff and
// for checking what the post-processors write. Comments — `( … )` and from `;` to the
// end of the line — and the tape's `%` marks (io/nc_line.hpp) are dropped (a nested or
// unclosed comment, or a lone `)`, is refused at its column, as a controller stops there); macro
// syntax (`#`, `[`, WHILE, IF) and Hollerith-like strings inside M98( … ) are kept as text words,
// compared literally.

#include <string>
#include <vector>

namespace freeturn {

struct NcWord {
  char letter = 0;      // upper case
  double value = 0;     // for a numeric word
  std::string text;     // the word as written (for non-numeric words and codes)
  bool numeric = true;
  int column = 0;  // 1-based column of its letter
};

struct NcBlock {
  int line = 0;  // 1-based line in its file
  int file = 0;  // read_nc_program: which of its files (0 the program, then each child read)
  std::vector<NcWord> words;
};

// Throws InputError (file:line:col) for text that is not NC: a character that starts no
// word, a letter without a value, or an axis (X Y Z A B C U V W) or F word given twice in
// one block (controllers either stop there or take one of the two; which is not ours to
// guess), or a '%' that is no tape mark (with words after it, or among a block's words).
// A line of '%' alone after the file's first line with anything on it is the tape's end
// (RS-274, io/nc_line.hpp): the controller reads nothing after it, and neither does this.
std::vector<NcBlock> parse_nc(const std::string& text, const std::string& file);

// A program file and the child files it calls (M98(name), beside it), as one sequence of
// blocks in the order the controller runs them. Each block keeps its own file's line.
// The run ends at the block that ends the program (M02 or M30 in any file, M99 in the
// main one) and a child returns at its M99: blocks after those are never run, so they are
// not read as motion.
// Throws InputError for a file that cannot be read or parsed, or a call nested deeper than
// the child files a post writes (one level). `files`, when given, receives the paths the
// blocks' `file` indices name.
std::vector<NcBlock> read_nc_program(const std::string& path,
                                     std::vector<std::string>* files = nullptr);

// The whole text of an NC program file. Only a regular file: a device (/dev/zero) would be
// read until memory runs out, and a pipe would block the open for good.
std::string read_nc_text(const std::string& path);

struct NcDiffOptions {
  double axis_tolerance = 1e-9;    // mm or degrees, for X Y Z A B C U V W I J K
  double other_tolerance = 1e-9;   // relative, for F, S, P and other numeric words
};

struct NcDiffResult {
  bool same = true;
  std::string first_difference;  // "a.nc:12 vs b.nc:12: X 1.000000 ≠ 1.000100 (Δ 1e-04)"
  double largest[26] = {0};      // per letter A…Z, the largest |Δ| seen in matched words
  long blocks_a = 0, blocks_b = 0;
};

// Compares two programs by what they make the machine do (io/nc_diff.cpp): the blocks
// that act (move an axis, or state an M or T code, a G code of no RS-274 modal group, or
// another word) pair up one to one, each pair in the same modal state (the modal groups'
// G codes, the axes' positions, F outside G93 and S, as the blocks up to it leave them),
// with the same stated codes and words; lengths and angles within `axis_tolerance`.
// Formatting (digits, spaces, word order within a block, line numbers N…), comments, and
// modal codes restated or set a line early do not count.
NcDiffResult nc_diff(const std::vector<NcBlock>& a, const std::string& name_a,
                     const std::vector<NcBlock>& b, const std::string& name_b,
                     const NcDiffOptions& options = {});
// The same for programs read with their child files (read_nc_program): `files_a` and
// `files_b` name the files the blocks' `file` indices point into. A call (M98) and a
// child's return (M99) are how a program is laid out in files, not what the machine does:
// a program written whole and the same one split into a main program and its point files
// are the same. M99 in a main program (its end) counts.
NcDiffResult nc_diff(const std::vector<NcBlock>& a, const std::vector<std::string>& files_a,
                     const std::vector<NcBlock>& b, const std::vector<std::string>& files_b,
                     const NcDiffOptions& options = {});
// Reads both programs as the controller runs them (read_nc_program) and compares them.
NcDiffResult nc_diff_files(const std::string& a, const std::string& b,
                           const NcDiffOptions& options = {});

}  // namespace freeturn
