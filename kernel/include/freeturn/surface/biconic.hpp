#pragma once
// Biconic: z = (c_x x² + c_y y²) / (1 + √(1 − (1+k_x) c_x² x² − (1+k_y) c_y² y²))
// (shared/notes/optical-surfaces.md). c = 0 is flat in that direction.

#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

class Biconic final : public JetSurface<Biconic> {
 public:
  Biconic(double cx, double cy, double kx, double ky) : cx_(cx), cy_(cy), kx_(kx), ky_(ky) {}
  const char* type() const override { return "biconic"; }
  double defined_radius() const override;
  double max_bend(double radius) const override;

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T x2 = x * x, y2 = y * y;
    const T q = sqrt(1.0 - (1 + kx_) * cx_ * cx_ * x2 - (1 + ky_) * cy_ * cy_ * y2);
    return (cx_ * x2 + cy_ * y2) / (1.0 + q);
  }

 private:
  double cx_, cy_, kx_, ky_;
};

}  // namespace freeturn
