// Precitech Nanoform (UPx controller), DIFFSYS-style data (shared/notes/nc-formats.md):
// ';' comment lines, then one "C…X…Z…" line per point with no spaces. Public facts are
// thin, so every code around the data — the header, switching PVT on, the footer — is a
// template in the machine YAML. The data lines carry no time: the controller runs them
// at one block time (PVT, paper 001), stated in the header from the program's constant
// block time; a program whose block times vary is refused unless `time_word` names a
// word to carry each block's time. Profile programs (X and Z only) run at the job's feed,
// stated once as a feed line.
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "freeturn/post_adapter.hpp"
#include "freeturn/post_format.hpp"

namespace {

using freeturn::post::append_number;
using freeturn::post::append_word;
using freeturn::post::PostError;

class PrecitechPost {
 public:
  PrecitechPost(const ft_program_info& info, const freeturn::post::Output& out,
                freeturn::post::FlatSettings& s)
      : info_(info), out_(out) {
    std::string message;
    if (!s.code_lines("header", "; PVT mode\\n; G08", header_, message) ||
        !s.code_lines("footer", "; end\\nM30", footer_, message) ||
        !s.code_lines("feed_line", "G01 F", feed_line_, message))
      throw PostError(message);
    // The feed's own line: the words before its value, which ends it.
    if (feed_line_.find('\n') != std::string::npos || feed_line_.empty() ||
        feed_line_.back() != 'F')
      throw PostError(
          "dialect setting 'feed_line' must be one line of words ending in F (the "
          "feed's value follows it), not '" +
          feed_line_ + "'");
    time_word_ = s.text("time_word", "");
    // A word letter of its own: not an axis of RS-274's (A B C U V W X Y Z: a time read as a
    // position, or on a lathe as an increment of X or Z), and not a code (G, M), a line
    // or program number (N, O), the feed (F) or the spindle speed (S).
    if (time_word_.size() > 1 ||
        (time_word_.size() == 1 &&
         (time_word_[0] < 'A' || time_word_[0] > 'Z' ||
          std::string_view("ABCUVWXYZGMNOFS").find(time_word_[0]) != std::string_view::npos)))
      throw PostError(
          "time_word must be one capital letter that is no axis (A B C U V W X Y Z), code (G "
          "M), number (N O), feed (F) or spindle speed (S), not '" +
          time_word_ + "'");
    profile_ = true;
    for (int i = 0; i < info.layout.count; ++i)
      if (info.layout.letters[i] == 'C') profile_ = false;
  }

  void begin() {
    std::string head = "; " + std::string(info_.program_name) + " for " + info_.machine_name +
                       ", written by freeturn\n; interpolation " +
                       (info_.interpolation == 1 ? "PVT" : "linear") + "\n" + header_ + "\n";
    if (profile_) {
      head += feed_line_;
      append_number(head, info_.feed, 3);
      head += "\n";
    }
    out_.put(head);
  }

  void blocks(const ft_block* b, std::size_t count) {
    const ft_axis_layout& l = info_.layout;
    line_.clear();  // the chunk's lines, handed to the host at once
    for (std::size_t k = 0; k < count; ++k) {
      if (!first_ && time_word_.empty() && !profile_) {
        if (block_time_ < 0) {
          block_time_ = b[k].time;
          line_ += "; block time ";
          append_number(line_, b[k].time, 9);
          line_ += " s\n";
        } else if (std::abs(b[k].time - block_time_) > 1e-9 * block_time_) {
          char message[256];
          std::snprintf(message, sizeof message,
                        "block times vary (%.9g s, then %.9g s) and this dialect writes none: use "
                        "equal-angle points, or set time_word in the machine's precitech settings",
                        block_time_, b[k].time);
          throw PostError(message);
        }
      }
      for (const char letter : {'C', 'X', 'Z', 'B'})
        for (int i = 0; i < l.count; ++i)
          if (l.letters[i] == letter) {
            const double v = letter == 'X' ? b[k].x : letter == 'Z' ? b[k].z : letter == 'C' ? b[k].c : b[k].b;
            append_word(line_, letter, v, l.decimals[i], letter == 'C' && info_.c_wrapped);
          }
      if (!first_ && !time_word_.empty()) append_word(line_, time_word_[0], b[k].time, 9);
      first_ = false;
      line_ += '\n';
    }
    out_.put(line_);
  }

  void end() { out_.put(footer_ + "\n"); }

 private:
  const ft_program_info& info_;
  const freeturn::post::Output& out_;
  std::string header_, footer_, time_word_, feed_line_;
  bool profile_ = false, first_ = true;
  double block_time_ = -1;
  std::string line_;  // reused: no allocation per block
};

}  // namespace

FREETURN_EXPORT_POST(PrecitechPost, "precitech")
