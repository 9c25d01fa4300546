#pragma once
// The design less weighted corrections, z = design(x, y) − Σ gain_k · correction_k(x, y):
// the surface a compensated job cuts (docs/metrology.md), each correction the form error a
// measured part showed, so that the next part comes out nearer the design.

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class CorrectedSurface final : public Surface {
 public:
  struct Correction {
    std::unique_ptr<Surface> error;  // the part's height beyond the design's (mm)
    double gain = 1;
  };

  CorrectedSurface(std::unique_ptr<Surface> design, std::vector<Correction> corrections)
      : design_(std::move(design)), corrections_(std::move(corrections)) {}

  const Surface& design() const { return *design_; }
  const std::vector<Correction>& corrections() const { return corrections_; }

  const char* type() const override { return design_->type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    design_->sag_gradient(x, y, z, zx, zy);
    for (const Correction& c : corrections_) {
      double e, ex, ey;
      c.error->sag_gradient(x, y, e, ex, ey);
      z -= c.gain * e;
      zx -= c.gain * ex;
      zy -= c.gain * ey;
    }
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    HeightDerivatives h = design_->height_derivatives(x, y);
    for (const Correction& c : corrections_) {
      const HeightDerivatives e = c.error->height_derivatives(x, y);
      h.z -= c.gain * e.z;
      h.zx -= c.gain * e.zx;
      h.zy -= c.gain * e.zy;
      h.zxx -= c.gain * e.zxx;
      h.zxy -= c.gain * e.zxy;
      h.zyy -= c.gain * e.zyy;
    }
    return h;
  }
  // Where the design and every correction have a value (a B-spline correction ends at its
  // square).
  double defined_radius() const override {
    double r = design_->defined_radius();
    for (const Correction& c : corrections_) r = std::min(r, c.error->defined_radius());
    return r;
  }
  // The corrections are smooth (Zernike polynomials): the creases are the design's.
  bool has_creases() const override { return design_->has_creases(); }
  bool may_have_ridges() const override { return design_->may_have_ridges(); }
  int section_creases(const RadialLine& line, double lo, double hi, std::span<double> out) const override {
    return design_->section_creases(line, lo, hi, out);
  }
  // Smooth corrections move no crease and change no slope's jump across one.
  int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const override {
    return design_->creases_near(x, y, radius, out);
  }

 private:
  std::unique_ptr<Surface> design_;
  std::vector<Correction> corrections_;
};

}  // namespace freeturn
