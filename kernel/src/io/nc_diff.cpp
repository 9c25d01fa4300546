// Two NC programs compared by what they make the machine do, not by how they are written.
//
// Each program is read as a controller reads it: G codes of RS-274's modal groups
// (LinuxCNC's table: motion, plane, distance, feed mode, units, cutter compensation, tool
// length, canned-cycle return, coordinate system, path control, spindle-speed mode, lathe
// diameter mode) hold until another of their group replaces them, and so do the axis
// positions, F (except in inverse time, G93, where each move states its own) and S. A
// block "acts" when it moves an axis or states anything that is not such modal state (an
// M or T code, a G code of no modal group or one the table does not know — a dialect's own
// G63 is compared where it is written —, a word such as P, a non-numeric word). The
// programs match when their acting blocks pair up one to one, each pair with the same
// modal state, the same stated codes and words, and axes within the tolerance. A line that
// only restates a modal code, or sets one a line before the move instead of on it, changes
// nothing.
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "freeturn/io/nc_line.hpp"
#include "freeturn/io/nc_program.hpp"

namespace freeturn {
namespace {

bool is_axis(char letter) { return std::string("XYZABCUVW").find(letter) != std::string::npos; }
// An arc's centre offsets: lengths, but stated by each arc (not modal).
bool is_offset(char letter) { return letter == 'I' || letter == 'J' || letter == 'K'; }

std::string code_text(char letter, double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%c%g", letter, value);
  return buf;
}

// A program's modal state, carried from block to block.
struct Modal {
  std::map<int, std::string> groups;  // group → its code ("G1")
  std::map<char, double> axes;
  std::map<char, double> values;  // F (outside G93), S
  bool inverse_time() const {
    const auto g = groups.find(5);
    return g != groups.end() && g->second == "G93";
  }
};

// What one acting block does.
struct Act {
  const NcBlock* block = nullptr;
  Modal modal;                      // the state it runs in, its own words applied
  std::set<std::string> codes;      // its M, T and non-modal G codes
  std::map<char, double> offsets;   // its arc centre offsets (I, J, K)
  std::map<char, double> values;    // its other numeric words (P, Q, R, …; F under G93)
  std::vector<std::string> text;    // its non-numeric words, literally
};

// `calls_followed`: the blocks hold each child's blocks where it is called
// (read_nc_program), so a call (M98) and a child's return (M99) are only the layout.
std::vector<Act> acts_of(const std::vector<NcBlock>& blocks, bool calls_followed) {
  std::vector<Act> acts;
  Modal modal;
  for (const NcBlock& block : blocks) {
    Act act;
    act.block = &block;
    bool acts_here = false;
    // Codes first: a block's G93 or G94 decides how its own F is read.
    for (const NcWord& w : block.words) {
      if (!w.numeric || w.letter != 'G') continue;
      const int group = g_code_modal_group(w.value);
      if (group > 0) {
        modal.groups[group] = code_text('G', w.value);
      } else {
        act.codes.insert(code_text('G', w.value));
        acts_here = true;
      }
    }
    for (const NcWord& w : block.words) {
      if (!w.numeric) {
        if (calls_followed && w.text.rfind("M98(", 0) == 0) continue;  // the child's blocks follow
        act.text.push_back(w.text);
        acts_here = true;
      } else if (w.letter == 'N' || w.letter == 'G') {
        continue;
      } else if (calls_followed && w.letter == 'M' && block.file > 0 && w.value == 99) {
        continue;  // a child's return: how the program is laid out in files
      } else if (w.letter == 'M' || w.letter == 'T') {
        act.codes.insert(code_text(w.letter, w.value));
        acts_here = true;
      } else if (is_axis(w.letter)) {
        modal.axes[w.letter] = w.value;
        acts_here = true;
      } else if (is_offset(w.letter)) {
        act.offsets[w.letter] = w.value;
        acts_here = true;
      } else if (w.letter == 'S' || (w.letter == 'F' && !modal.inverse_time())) {
        modal.values[w.letter] = w.value;
      } else {
        act.values[w.letter] = w.value;
        acts_here = true;
      }
    }
    if (!acts_here) continue;
    act.modal = modal;
    acts.push_back(std::move(act));
  }
  return acts;
}

std::string codes_text(const std::set<std::string>& codes) {
  std::string s;
  for (const std::string& c : codes) s += (s.empty() ? "" : " ") + c;
  return s.empty() ? "none" : s;
}

std::string group_text(const std::map<int, std::string>& groups, int group) {
  const auto g = groups.find(group);
  return g == groups.end() ? "none" : g->second;
}

NcDiffResult compare(const std::vector<NcBlock>& a, const std::vector<std::string>& files_a,
                     const std::vector<NcBlock>& b, const std::vector<std::string>& files_b,
                     const NcDiffOptions& o, bool calls_followed) {
  const auto name = [](const std::vector<std::string>& files, const NcBlock& block) {
    const auto k = static_cast<std::size_t>(block.file);
    return k < files.size() ? files[k] : std::string("?");
  };
  const std::string name_a = files_a.empty() ? "?" : files_a[0];
  const std::string name_b = files_b.empty() ? "?" : files_b[0];
  NcDiffResult r;
  r.blocks_a = static_cast<long>(a.size());
  r.blocks_b = static_cast<long>(b.size());
  const std::vector<Act> acts_a = acts_of(a, calls_followed), acts_b = acts_of(b, calls_followed);
  const auto differ = [&](const Act& x, const Act& y, const std::string& what) {
    if (r.same) {
      r.same = false;
      r.first_difference = name(files_a, *x.block) + ":" + std::to_string(x.block->line) + " vs " +
                           name(files_b, *y.block) + ":" + std::to_string(y.block->line) + ": " +
                           what;
    }
  };
  // Words by value: `axis` ones (mm or degrees) within the absolute tolerance, the others
  // relative to their size.
  const auto compare = [&](const Act& x, const Act& y, const std::map<char, double>& va,
                           const std::map<char, double>& vb, bool axis) {
    std::set<char> letters;
    for (const auto& [l, v] : va) letters.insert(l);
    for (const auto& [l, v] : vb) letters.insert(l);
    for (const char l : letters) {
      const auto ia = va.find(l), ib = vb.find(l);
      if (ia == va.end() || ib == vb.end()) {
        differ(x, y, (axis ? std::string("axis ") : std::string()) + l + " only in one program");
        continue;
      }
      const double d = std::abs(ia->second - ib->second);
      r.largest[l - 'A'] = std::max(r.largest[l - 'A'], d);
      const bool same = axis ? d <= o.axis_tolerance
                             : d <= o.other_tolerance * std::max(1.0, std::abs(ia->second));
      if (!same) {
        char buf[128];
        if (axis)
          std::snprintf(buf, sizeof buf, "%c %.12g ≠ %.12g (Δ %.3g)", l, ia->second, ib->second, d);
        else
          std::snprintf(buf, sizeof buf, "%c %.12g ≠ %.12g", l, ia->second, ib->second);
        differ(x, y, buf);
      }
    }
  };
  const std::size_t n = std::min(acts_a.size(), acts_b.size());
  for (std::size_t k = 0; k < n; ++k) {
    const Act &x = acts_a[k], &y = acts_b[k];
    if (x.codes != y.codes)
      differ(x, y, "different codes: " + codes_text(x.codes) + " vs " + codes_text(y.codes));
    for (const auto& [group, code] : x.modal.groups)
      if (group_text(y.modal.groups, group) != code)
        differ(x, y, "modal " + code + " vs " + group_text(y.modal.groups, group));
    for (const auto& [group, code] : y.modal.groups)
      if (group_text(x.modal.groups, group) != code)
        differ(x, y, "modal " + group_text(x.modal.groups, group) + " vs " + code);
    if (x.text != y.text) differ(x, y, "different words");
    compare(x, y, x.modal.axes, y.modal.axes, true);
    compare(x, y, x.offsets, y.offsets, true);
    compare(x, y, x.modal.values, y.modal.values, false);
    compare(x, y, x.values, y.values, false);
  }
  if (acts_a.size() != acts_b.size() && r.same) {
    r.same = false;
    r.first_difference = name_a + " has " + std::to_string(acts_a.size()) + " blocks that act, " +
                         name_b + " has " + std::to_string(acts_b.size());
  }
  return r;
}

}  // namespace

NcDiffResult nc_diff(const std::vector<NcBlock>& a, const std::string& name_a,
                     const std::vector<NcBlock>& b, const std::string& name_b,
                     const NcDiffOptions& o) {
  return compare(a, {name_a}, b, {name_b}, o, false);
}

NcDiffResult nc_diff(const std::vector<NcBlock>& a, const std::vector<std::string>& files_a,
                     const std::vector<NcBlock>& b, const std::vector<std::string>& files_b,
                     const NcDiffOptions& o) {
  return compare(a, files_a, b, files_b, o, true);
}

NcDiffResult nc_diff_files(const std::string& a, const std::string& b, const NcDiffOptions& o) {
  std::vector<std::string> files_a, files_b;
  const std::vector<NcBlock> blocks_a = read_nc_program(a, &files_a);
  const std::vector<NcBlock> blocks_b = read_nc_program(b, &files_b);
  return nc_diff(blocks_a, files_a, blocks_b, files_b, o);
}

}  // namespace freeturn
