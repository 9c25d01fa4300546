#pragma once
// A design seen by a nose too large for some of its troughs (docs/tool.md, "Troughs tighter
// than the nose").
//
// Where a smooth section bends toward the tool more tightly than the nose (its curvature
// g''/(1 + g'²)^{3/2} above 1/R), the nose's offset folds into a swallowtail: no placement
// of the nose touches the design there, and the offsets of the trough's two sides cross.
// The nose that stays above the design rests on both sides at that crossing, as it rests
// in a crease sharper than itself, and leaves the trough's bottom uncut. This view lists
// such troughs as creases (Surface::section_creases), so that the envelope that holds the
// nose at creases (path/section_envelope.hpp) holds it there too: at each tight stretch of
// a section, a crease at its two ends and at its tightest point. Everything else is the
// design's own.

#include <vector>

#include "freeturn/core/instance_id.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

namespace detail {
struct LineTroughs;  // one line's troughs, as a thread keeps them (tight_troughs.cpp)
}

class TightTroughs final : public Surface {
 public:
  // design: must outlive the view. placed_radius: the radius the nose's centre is placed
  // at (the nose radius plus the stand-off, mm, > 0). outer_radius: the aperture's.
  TightTroughs(const Surface& design, double placed_radius, double outer_radius);

  // Whether any section within the aperture bends more tightly than the nose (sampled on a
  // polar grid): where none does, the view adds nothing and need not be used.
  bool any() const { return any_; }

  const char* type() const override { return s_.type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    s_.sag_gradient(x, y, z, zx, zy);
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    return s_.height_derivatives(x, y);
  }
  double defined_radius() const override { return s_.defined_radius(); }
  bool has_creases() const override { return true; }
  bool may_have_ridges() const override { return s_.may_have_ridges(); }
  int section_creases(const RadialLine& line, double lo, double hi,
                      std::span<double> out) const override;
  int line_creases(double x0, double y0, const RadialLine& line, double lo, double hi,
                   std::span<double> out) const override;
  double max_bend(double radius) const override { return s_.max_bend(radius); }
  double max_slope(double radius) const override { return s_.max_slope(radius); }
  double max_section_bend(double radius) const override { return s_.max_section_bend(radius); }
  // Not known: a trough's crease is no curve with a bounded slope jump.
  int creases_near(double, double, double, std::span<NearbyCrease>) const override { return -1; }
  bool crease_circles(std::vector<CreaseCircle>&) const override { return false; }

 private:
  // The creases of the tight stretches along the line through (x0, y0) that reach into its
  // samples [first, last] (whole steps of ρ), into a LineTroughs (tight_troughs.cpp).
  void sample(double x0, double y0, const RadialLine& line, long first, long last,
              detail::LineTroughs& out) const;
  // Over the polar grid at the current step (256 radial lines): the tight stretches
  // found, and how many of them are narrow ones the samples do not resolve.
  void count_tight_stretches(long& runs, long& narrow) const;

  const Surface& s_;
  double R_, step_, limit_;
  int per_radius_;  // samples per R', step_ = R_ / per_radius_
  bool any_ = false;
  InstanceId id_;  // keys each thread's cache of its last line
};

}  // namespace freeturn
