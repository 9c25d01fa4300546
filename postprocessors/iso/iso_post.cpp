// ISO 6983 / RS-274 G-code that LinuxCNC's interpreter accepts (shared/notes/nc-formats.md):
// G21 (metric; never G71, a lathe cycle in LinuxCNC 2.9), G18 (ZX plane), G8 (radius
// mode), inverse-time feed G93 with F on every G1 line (F = 1 / block time in minutes),
// C accumulating, no Moore-only codes. Comments in parentheses.
#include <string>

#include "freeturn/post_adapter.hpp"
#include "freeturn/post_format.hpp"

namespace {

using freeturn::post::append_number;
using freeturn::post::append_word;
using freeturn::post::PostError;

class IsoPost {
 public:
  IsoPost(const ft_program_info& info, const freeturn::post::Output& out,
          freeturn::post::FlatSettings& settings)
      : info_(info), out_(out) {
    std::string message;
    // Approach and retract run `retract` beyond the host's clearance base (top_z: no block
    // rises past it), so no rapid move on the way in or out touches the part.
    if (!settings.number_in("retract", 1.0, 0.01, 500, retract_, message) ||
        !settings.number_in("approach_feed", 20.0, 0.001, 10000, approach_feed_, message))
      throw PostError(message);
    for (int i = 0; i < info.layout.count; ++i)
      if (info.layout.letters[i] == 'Z') z_decimals_ = info.layout.decimals[i];
    clear_z_ = freeturn::post::clearance_z(info.top_z, info.z_away, retract_, z_decimals_);
  }

  void begin() {
    out_.put("%\n(" + std::string(info_.program_name) + " for " + info_.machine_name +
             ", written by freeturn)\nG21 G18 G8 G90 G40 G94\n");
  }

  // The chunk's lines are handed to the host at once: one write per chunk, not per line.
  void blocks(const ft_block* b, std::size_t count) {
    line_.clear();
    for (std::size_t k = 0; k < count; ++k) {
      if (first_) {
        // Approach: up, over, then down at a slow feed, then inverse-time feed.
        first_ = false;
        line_ += "G0 ";
        append_word(line_, 'Z', clear_z_, z_decimals_);
        line_ += "\nG0";
        for (int i = 0; i < info_.layout.count; ++i)
          if (info_.layout.letters[i] != 'Z') word(b[k], i);
        line_ += "\nG1 ";
        append_word(line_, 'Z', b[k].z, z_decimals_);
        line_ += " F";
        append_number(line_, approach_feed_, 3);
        if (info_.feed_per_minute) {
          line_ += "\nF";
          append_number(line_, info_.feed, 3);
          line_ += '\n';
        } else {
          line_ += "\nG93\n";
        }
      } else {
        if (!(b[k].time > 0)) throw PostError("a block has no duration");
        line_ += "G1";
        for (int i = 0; i < info_.layout.count; ++i) word(b[k], i);
        if (!info_.feed_per_minute) {
          // LinuxCNC's G93: F = 1 / (block time in minutes), on every G1 line.
          line_ += " F";
          append_number(line_, 60.0 / b[k].time, 6);
        }
        line_ += '\n';
      }
    }
    out_.put(line_);
  }

  void end() {
    std::string tail = "G94\nG0 ";
    append_word(tail, 'Z', clear_z_, z_decimals_);
    out_.put(tail + "\nM2\n%\n");
  }

 private:
  void word(const ft_block& b, int i) {
    const char letter = info_.layout.letters[i];
    const double v = letter == 'X' ? b.x : letter == 'Z' ? b.z : letter == 'C' ? b.c : b.b;
    line_ += ' ';
    append_word(line_, letter, v, info_.layout.decimals[i], letter == 'C' && info_.c_wrapped);
  }

  const ft_program_info& info_;
  const freeturn::post::Output& out_;
  double retract_ = 1.0, approach_feed_ = 20;
  double clear_z_ = 0;
  int z_decimals_ = 6;
  bool first_ = true;
  std::string line_;  // a chunk's lines, reused: no allocation per block
};

}  // namespace

FREETURN_EXPORT_POST(IsoPost, "iso")
