// Moore Nanotech, NanoCAM-style slow-tool-servo programs (shared/notes/nc-formats.md):
// a header (metric, ZX plane, tool offset, C homing with M80), inverse-time feed G93 with
// F the block time in seconds (modal: written when it changes), one "C… X… Z…" line per
// point (B too on 4-axis machines), C wrapped to [0, 360), and a footer that leaves
// C-axis mode (M79). Long programs are split: the main program calls child point files
// with M98(<name>_NNN.nc), each ending in M99. The codes whose meaning public programs do
// not settle (the header and footer lines) come from the machine YAML.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "freeturn/post_adapter.hpp"
#include "freeturn/post_format.hpp"

namespace {

using freeturn::post::append_number;
using freeturn::post::append_word;
using freeturn::post::PostError;

class MoorePost {
 public:
  MoorePost(const ft_program_info& info, const freeturn::post::Output& out,
            freeturn::post::FlatSettings& s)
      : info_(info), out_(out) {
    std::string message;
    double time_decimals = 6;
    // Approach and retract run `retract` beyond the host's clearance base (top_z: no block
    // rises past it), so no move on the way in or out touches the part. G93's F is the
    // block time: with no decimals every short block would read F0. The host schedules
    // block times in whole microseconds, within the axes' limits as written (docs/
    // machines.md, "Scheduling"): fewer than 6 decimals would round them to other times,
    // and the axes' accelerations with them (3 decimals took the demo's C to 2.9 times its
    // limit, read back from the program).
    if (!s.number_in("retract", 1.0, 0.01, 500, retract_, message) ||
        !s.number_in("approach_feed", 200.0, 0.001, 10000, approach_feed_, message) ||
        !s.whole_number_in("child_blocks", 0.0, 0, 1e8, child_blocks_, message) ||
        !s.whole_number_in("time_decimals", 6.0, 6, 9, time_decimals, message))
      throw PostError(message);
    // A child file per handful of points would be thousands of files for one part.
    if (child_blocks_ != 0 && child_blocks_ < 100)
      throw PostError("dialect setting 'child_blocks' is " + s.text("child_blocks", "") +
                      ": 0 (one program) or at least 100 points per child file");
    time_decimals_ = static_cast<int>(time_decimals);
    // The spindle's code is one word, M03 or M04: it is written on the line of S, where any
    // other text (a move, a second line) would reach the controller unchecked.
    if (!s.code_lines("header",
                      "G71 G01 G18 G40 G63 G90 G94 G54\\nT0101\\nG53 Z-180.\\nM80\\nG09 "
                      "C0.0\\nG92 C0.0",
                      header_, message) ||
        !s.code_lines("footer", "G53 Z-180.\\nM79\\nG52\\nT0000\\nM30", footer_, message) ||
        !s.one_of("spindle", "M03", {"M03", "M04", "M3", "M4"}, spindle_, message))
      throw PostError(message);
    bool has_c = false;
    for (int i = 0; i < info.layout.count; ++i) has_c = has_c || info.layout.letters[i] == 'C';
    if (!has_c) throw PostError("the moore post writes slow-tool-servo programs: the machine needs a C axis");
    for (int i = 0; i < info.layout.count; ++i)
      if (info.layout.letters[i] == 'Z') z_decimals_ = info.layout.decimals[i];
    // The axis words of a block, C first as NanoCAM writes them, then X, Z, B.
    for (const char letter : {'C', 'X', 'Z', 'B'})
      for (int i = 0; i < info.layout.count && i < 4; ++i)
        if (info.layout.letters[i] == letter) word_axes_[word_count_++] = i;
    clear_z_ = freeturn::post::clearance_z(info.top_z, info.z_away, retract_, z_decimals_);
  }

  void begin() {
    // S has 3 decimals: a speed under half a thousandth of an rpm (a job's typo, or the one
    // speed a constant-rpm schedule found every block allows) would command S0.000, a
    // stopped spindle under a program that cuts.
    std::string speed;
    append_number(speed, info_.spindle_rpm, 3);
    if (speed.find_first_of("123456789") == std::string::npos) {
      char rpm[32];
      std::snprintf(rpm, sizeof rpm, "%.6g", info_.spindle_rpm);
      throw PostError(std::string("a spindle speed of ") + rpm + " rpm reads S" + speed +
                      " (3 decimals): the spindle would stand still");
    }
    std::string head = "( " + std::string(info_.program_name) + " for " + info_.machine_name +
                       ", written by freeturn )\n" + header_ + "\n" + spindle_ + " S" + speed;
    out_.put(head + "\n");
  }

  // The chunk's lines are handed to the host at once (one write per chunk, not per line),
  // and before the program switches files.
  void blocks(const ft_block* b, std::size_t count) {
    line_.clear();
    for (std::size_t k = 0; k < count; ++k) {
      if (first_) {
        // Approach in feed per minute: to the clearance height in Z alone, then the
        // rotary axes alone (a feed per minute times a turn only where no linear axis
        // moves with it: beside X it takes X's time, and where X was is not written), over
        // the first point at that height, and down to the point. The clearance bounds the
        // nose for any B (tool/clearance.hpp), so B may turn there.
        first_ = false;
        ft_block above = b[k];
        above.z = clear_z_;
        line_ += "G94 G01 ";
        append_word(line_, 'Z', clear_z_, z_decimals_);
        line_ += " F";
        append_number(line_, approach_feed_, 3);
        line_ += "\n";
        if (words(above, kRotaryWords)) line_ += "\n";
        words(above);
        line_ += "\n";
        words(b[k]);
        line_ += '\n';
        continue;
      }
      if (child_blocks_ > 0 && in_child_ == 0) {
        // A new child point file, called from the main program.
        char name[512];
        std::snprintf(name, sizeof name, "%s_%03d.nc", info_.program_name, ++children_);
        out_.put(line_);
        line_.clear();
        out_.select_main();
        out_.put(std::string("M98(") + name + ")\n");
        out_.open_file(name);
        last_feed_length_ = 0;  // every child states its feed
      }
      // F is modal: written when its text changes, not when the double behind it does
      // (blocks of 0.1333331 s and 0.1333334 s both read F0.133333).
      char feed[freeturn::post::kNumberCapacity];
      const int feed_length = freeturn::post::format_fixed(b[k].time, time_decimals_, feed);
      if (feed_length == 0) throw freeturn::post::unwritable('F', b[k].time, time_decimals_);
      // A few bytes, compared in place (a call to memcmp per block cost more).
      bool same_feed = feed_length == last_feed_length_;
      for (int i = 0; same_feed && i < feed_length; ++i) same_feed = feed[i] == last_feed_[i];
      if (!same_feed) {
        if (!(std::nearbyint(b[k].time * time_scale()) > 0)) {
          std::string message = "a block time of ";
          append_number(message, b[k].time, 9);
          throw PostError(message + " s reads F0 at " + std::to_string(time_decimals_) +
                          " decimals: raise time_decimals");
        }
        line_ += "G93 F";
        line_.append(feed, static_cast<std::size_t>(feed_length));
        line_ += '\n';
        std::memcpy(last_feed_, feed, static_cast<std::size_t>(feed_length));
        last_feed_length_ = feed_length;
      }
      words(b[k]);
      line_ += '\n';
      if (child_blocks_ > 0 && ++in_child_ >= static_cast<long long>(child_blocks_)) {
        line_ += "M99\n";
        in_child_ = 0;
      }
    }
    out_.put(line_);
  }

  void end() {
    if (child_blocks_ > 0 && in_child_ > 0) out_.put("M99\n");
    if (children_ > 0) out_.select_main();
    std::string tail = "G94\nG01 ";
    append_word(tail, 'Z', clear_z_, z_decimals_);
    tail += " F";
    append_number(tail, approach_feed_, 3);
    out_.put(tail + "\n" + footer_ + "\n");
  }

 private:
  double time_scale() const { return freeturn::post::decimal_scale(time_decimals_); }

  enum Words { kAllWords, kRotaryWords };

  // The axis words of a block (the order of word_axes_), appended to the line once: the
  // words are formatted into a buffer on the stack, not appended one by one. `which`:
  // every axis, or the rotary ones alone; returns whether it wrote a word.
  bool words(const ft_block& b, Words which = kAllWords) {
    const ft_axis_layout& l = info_.layout;
    char text[4 * (freeturn::post::kNumberCapacity + 2)];
    int length = 0;
    for (int w = 0; w < word_count_; ++w) {
      const int i = word_axes_[w];
      const char letter = l.letters[i];
      if (which == kRotaryWords && letter != 'C' && letter != 'B') continue;
      const double v = letter == 'X' ? b.x : letter == 'Z' ? b.z : letter == 'C' ? b.c : b.b;
      if (length > 0) text[length++] = ' ';
      length += freeturn::post::format_word(letter, v, l.decimals[i],
                                            letter == 'C' && info_.c_wrapped, text + length);
    }
    if (!line_.empty() && line_.back() != '\n' && length > 0) line_.push_back(' ');
    line_.append(text, static_cast<std::size_t>(length));
    return length > 0;
  }

  const ft_program_info& info_;
  const freeturn::post::Output& out_;
  std::string header_, footer_, spindle_;
  double retract_ = 1.0, approach_feed_ = 200, child_blocks_ = 0;
  int time_decimals_ = 6;
  bool first_ = true;
  double clear_z_ = 0;
  char last_feed_[freeturn::post::kNumberCapacity] = {};  // the last F text written
  int last_feed_length_ = 0;                              // 0: none yet in this file
  int word_axes_[4] = {0, 0, 0, 0};                       // layout indices, in word order
  int word_count_ = 0;
  int z_decimals_ = 6;
  long long in_child_ = 0;
  int children_ = 0;
  std::string line_;  // reused: no allocation per block
};

}  // namespace

FREETURN_EXPORT_POST(MoorePost, "moore")
