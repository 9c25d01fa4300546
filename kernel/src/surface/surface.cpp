#include "freeturn/surface/surface.hpp"

namespace freeturn {

Eigen::Vector3d Surface::normal(double x, double y) const {
  double z, zx, zy;
  sag_gradient(x, y, z, zx, zy);
  return Eigen::Vector3d(-zx, -zy, 1.0).normalized();
}

}  // namespace freeturn
