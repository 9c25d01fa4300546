#pragma once
// The one gate every NC byte passes (docs/robustness.md): numbers that must never reach a
// machine are stopped here, whatever produced them.
//
// Before a post-processor formats a block, the block's values must be finite and inside
// the machine's travel (and B inside its limits). After, every line the plugin wrote is
// read back outside its comments: each number must be finite and parse whole, the text
// must hold no "nan" or "inf", no F word may read 0 (a feed or a block time), and each
// axis word of the machine's layout must lie inside the travel within half a unit of its
// declared decimals (except on lines that leave the work frame: G53, G92), and no line with
// a word may follow the file's end (M02, M30, M99: a controller never runs it, so the cut
// the report describes would not be made). A line's comments must be ones a controller
// reads (none nested, none left open, no lone ')'), its G codes one per modal group, and
// its axis words and child calls must stand in the modes the program's words assume
// (absolute millimetres, radius mode, no cutter compensation, straight moves, feeds by
// time: io/nc_line.hpp); no preset (G10, G52, G92) may move an axis' frame. Under a feed per
// minute (G94), no linear axis may go faster than its max_velocity, nor a rotary one turning
// alone; a rotary axis may not turn together with a linear one, as its speed would follow
// from the linear move's length (a feed per minute times linear axes only). The first
// violation is kept with its file and line; PostProgram turns it into an error naming the
// plugin, and no NC file is committed.

#include <string>
#include <string_view>
#include <vector>

#include "freeturn/io/nc_line.hpp"
#include "freeturn/machine/axis_record.hpp"
#include "freeturn/machine/machine.hpp"

namespace freeturn {

class NcGuard {
 public:
  explicit NcGuard(const MachineDescription& machine);

  // "" when the record may be formatted, else why not. block: its index in the program.
  std::string check_record(const AxisRecord& record, long long block) const;

  // The plugin's output, in pieces of any size, to the file `index` (0: the main program,
  // then each child in the order opened); each file keeps its own line count and size.
  void select_file(std::size_t index, const std::string& name);
  void feed(std::string_view bytes);
  void end_files();  // last lines without their newline

  bool ok() const { return reason_.empty(); }
  const std::string& reason() const { return reason_; }  // with "file:line: "
  // The bound a written axis word crossed: its letter (0 for any other refusal) and
  // whether it was the upper one.
  struct Crossed {
    char letter = 0;
    bool upper = false;
    bool velocity = false;  // a feed per minute beyond the letter's max_velocity instead
  };
  Crossed crossed() const { return crossed_; }
  long long file_bytes() const { return files_[current_].bytes; }

 private:
  void check_line(std::string_view line);
  void refuse(const std::string& what);

  struct Range {
    bool checked = false;
    double min = 0, max = 0;
    // A number with at most this many significant integer digits is inside on the side of
    // its sign (−1: none is known to be).
    int digits_above = -1, digits_below = -1;
  };
  struct File {
    std::string name, line;  // the line being written
    long long lines = 0, bytes = 0;
    long long ended_at = 0;  // the line with the file's end word (M02, M30, M99, %), 0: none yet
    std::string end_word;
    bool blank_so_far = true;  // no line with anything on it yet: a '%' here starts the tape
    NcModeState modes;         // as this file's lines set them (a child opens in its caller's)
    // The modal motion and feed: G0 rather than G1, G94 (a controller's power-on default)
    // rather than G93, and the last F as written ("": none yet).
    bool rapid = false, per_minute = true;
    std::string feed;
    double feed_value = 0;  // feed read as a number (NaN: not yet)
  };
  // The last angle written for a rotary axis (A, B, C), as its word's number: a feed move
  // per minute that turns one together with a linear axis is judged against it. Kept
  // across the lines of one file in the order written; unknown (length −1) at a file's
  // start, after a switch of file, and after a move outside the work frame.
  struct RotaryAngle {
    char text[24];
    int length = -1;
  };
  RotaryAngle rotary_[3];
  Range ranges_[26];  // per letter A…Z
  double max_velocity_[26];  // per letter: mm/s or °/s (infinite: not an axis, or no limit)
  std::vector<File> files_;
  std::size_t current_ = 0;
  std::string reason_;
  std::string code_;  // check_line's words outside comments, lower case (reused: no allocation a line)
  Crossed crossed_;
};

}  // namespace freeturn
