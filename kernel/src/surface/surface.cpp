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

}  // namespace freeturn
