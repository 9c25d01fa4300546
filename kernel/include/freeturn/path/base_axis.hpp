#pragma once
// The axis of a base surface of revolution, in the design surface's frame: direction
// t = R_y(tilt_y) R_x(tilt_x) e_z (the tilts of TransformedSurface), through the point
// (shift_x, shift_y, 0).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace freeturn {

struct BaseAxis {
  double tilt_x = 0, tilt_y = 0;    // rad
  double shift_x = 0, shift_y = 0;  // mm

  Eigen::Vector3d direction() const {
    return {std::cos(tilt_x) * std::sin(tilt_y), -std::sin(tilt_x),
            std::cos(tilt_x) * std::cos(tilt_y)};
  }
  Eigen::Vector3d point() const { return {shift_x, shift_y, 0.0}; }
};

}  // namespace freeturn
