#pragma once

#include <algorithm>
#include <cmath>
#include <span>

namespace freeturn {

// Collects the creases a line meets into a caller's buffer (Surface::section_creases): keeps
// the lowest out.size() of them, ascending, and counts every one, so that a caller told of
// more than it holds knows its list is complete only up to its last entry. Creases are
// found in no order (lenslet by lenslet, knot line by knot line): keeping the first ones
// found, as before December 2026, left out creases anywhere in the list, and a nose placed
// from it missed a bowl's rim (a microlens mold whose pitch was under the nose's radius).
// A crease within `merge` of one kept is the same crease (two rims through one point). No
// allocation.
class CreaseSink {
 public:
  // out: the buffer; [lo, hi]: the stretch of the line asked for (others are not counted).
  CreaseSink(std::span<double> out, double lo, double hi, double merge = 1e-12)
      : out_(out), lo_(lo), hi_(hi), merge_(merge) {}

  void add(double rho) {
    if (!(rho >= lo_ && rho <= hi_)) return;
    for (int k = 0; k < kept_; ++k)
      if (std::abs(out_[static_cast<std::size_t>(k)] - rho) <= merge_) return;
    ++found_;
    if (kept_ < static_cast<int>(out_.size())) {
      out_[static_cast<std::size_t>(kept_++)] = rho;
      return;
    }
    // Full: the new crease displaces the highest kept, if it lies below it.
    if (kept_ == 0) return;
    double* highest = std::max_element(out_.data(), out_.data() + kept_);
    if (rho < *highest) *highest = rho;
  }

  // Sorts the kept creases; how many were found (more than out.size() where some were left
  // out: those above the last one kept).
  int finish() {
    // By insertion: a line meets a lenslet array's rims nearly in order, and std::sort's
    // guard on short arrays trips GCC 12's array-bounds warning.
    for (int i = 1; i < kept_; ++i) {
      const double v = out_[static_cast<std::size_t>(i)];
      int j = i;
      for (; j > 0 && out_[static_cast<std::size_t>(j - 1)] > v; --j)
        out_[static_cast<std::size_t>(j)] = out_[static_cast<std::size_t>(j - 1)];
      out_[static_cast<std::size_t>(j)] = v;
    }
    return found_;
  }

 private:
  std::span<double> out_;
  double lo_, hi_, merge_;
  int kept_ = 0, found_ = 0;
};

}  // namespace freeturn
