#pragma once
// Choosing the base surface for a spiral (paper 000, §4): a plane (the traditional
// spiral), the least-squares surface of revolution, or the minimax one; optionally about a
// searched axis; then the quasi-revolution test against a limit.
//
// When the axis moves, the part is to be mounted on it: the design is re-expressed in the
// axis frame (a TransformedSurface: the axis's crossing of the design at the origin, the
// axis along +z), sampled again there, and the base fitted again about z, so that the
// spiral, the test and the NC program all work in the frame the lathe will see.

#include <memory>
#include <string>
#include <vector>

#include "freeturn/path/base_axis.hpp"
#include "freeturn/path/base_surface.hpp"
#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/minimax_base_fit.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

enum class BaseKind { kPlane, kLeastSquares, kMinimax };

struct BasePlanOptions {
  BaseKind kind = BaseKind::kLeastSquares;
  bool search_axis = false;  // kMinimax only
  double angle_limit = 0;    // α_lim (rad); 0: no limit
  bool refuse_above_limit = true;  // else a warning
  int radial_samples = 48, angular_samples = 96;
  BaseFitOptions fit;
  MinimaxBaseOptions minimax;
};

struct BasePlan {
  BaseSurface base = BaseSurface::plane(1);
  BaseAxis axis;  // in the design's own frame
  // Where the searched axis crosses the design (its frame, mm): the program's origin.
  Eigen::Vector3d axis_crossing = Eigen::Vector3d::Zero();
  QuasiRevolution quasi_revolution;  // of the design (in the frame it is cut in) on `base`
  // The design in the axis frame when the axis moved (it refers to the design passed in,
  // which must outlive it); null when the design is cut in its own frame.
  std::unique_ptr<Surface> design_about_axis;
  std::vector<std::string> warnings;

  const Surface& design_to_cut(const Surface& design) const {
    return design_about_axis ? *design_about_axis : design;
  }
};

// Throws InputError, naming where α is largest, when α_max exceeds the limit and
// refuse_above_limit is set.
BasePlan plan_base_surface(const Surface& design, double inner_radius, double outer_radius,
                           const BasePlanOptions& options);

}  // namespace freeturn
