#include "freeturn/surface/biconic.hpp"

#include <algorithm>
#include <cmath>

namespace freeturn {

double Biconic::defined_radius() const {
  // 1 − a_x x² − a_y y² > 0 on the whole disk of radius r when r² · max(a_x, a_y) < 1.
  const double g = std::max((1 + kx_) * cx_ * cx_, (1 + ky_) * cy_ * cy_);
  return g > 0 ? 1.0 / std::sqrt(g) : Surface::defined_radius();
}

}  // namespace freeturn
