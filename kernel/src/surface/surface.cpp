#include "freeturn/surface/surface.hpp"

namespace freeturn {

double Surface::sag(double x, double y) const {
  double z, zx, zy;
  sag_gradient(x, y, z, zx, zy);
  return z;
}

Eigen::Vector3d Surface::point(double x, double y) const {
  return {x, y, sag(x, y)};
}

Eigen::Vector3d Surface::normal(double x, double y) const {
  double z, zx, zy;
  sag_gradient(x, y, z, zx, zy);
  return Eigen::Vector3d(-zx, -zy, 1.0).normalized();
}

int Surface::section_creases(const RadialLine&, double rho_lo, double rho_hi, std::span<double> out) const {
  if (!has_creases() || out.empty() || !(rho_lo <= 0 && 0 <= rho_hi)) return 0;
  out[0] = 0;
  return 1;
}

bool Surface::crease_circles(std::vector<CreaseCircle>&) const {
  return !has_creases();
}

int Surface::line_creases(double x0, double y0, const RadialLine& line, double rho_lo,
                          double rho_hi, std::span<double> out) const {
  if (x0 == 0 && y0 == 0) return section_creases(line, rho_lo, rho_hi, out);
  return has_creases() ? -1 : 0;
}

double Surface::max_bend(double) const { return std::numeric_limits<double>::infinity(); }

double Surface::max_slope(double) const {
  return std::numeric_limits<double>::infinity();
}

int Surface::creases_near(double, double, double, std::span<NearbyCrease>) const {
  return has_creases() ? -1 : 0;
}

}  // namespace freeturn
