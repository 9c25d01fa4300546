#pragma once
// A surface seen through a reference, raised along z by `raise` mm: the design a
// roughing pass cuts (the stock it leaves above the finish), or, with raise 0, a
// non-owning view of a caller's surface for a wrapper that wants to own its parent
// (TransformedSurface). The viewed surface must outlive the view.

#include "freeturn/surface/surface.hpp"

namespace freeturn {

class RaisedSurface final : public Surface {
 public:
  explicit RaisedSurface(const Surface& surface, double raise = 0) : s_(surface), raise_(raise) {}
  const char* type() const override { return s_.type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    s_.sag_gradient(x, y, z, zx, zy);
    z += raise_;
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    HeightDerivatives h = s_.height_derivatives(x, y);
    h.z += raise_;
    return h;
  }
  double defined_radius() const override { return s_.defined_radius(); }
  bool has_creases() const override { return s_.has_creases(); }
  bool may_have_ridges() const override { return s_.may_have_ridges(); }
  int section_creases(const RadialLine& line, double lo, double hi, std::span<double> out) const override {
    return s_.section_creases(line, lo, hi, out);
  }
  double max_bend(double radius) const override { return s_.max_bend(radius); }
  double max_slope(double radius) const override { return s_.max_slope(radius); }
  double max_section_bend(double radius) const override { return s_.max_section_bend(radius); }
  int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const override {
    return s_.creases_near(x, y, radius, out);
  }

 private:
  const Surface& s_;
  double raise_;
};

}  // namespace freeturn
