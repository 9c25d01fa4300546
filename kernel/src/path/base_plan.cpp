#include "freeturn/path/base_plan.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/surface/height_field_queries.hpp"
#include "freeturn/surface/raised_surface.hpp"
#include "freeturn/surface/transformed_surface.hpp"

namespace freeturn {
namespace {

std::string degrees(double rad) { return fixed_text(rad * 180 / std::numbers::pi, 6); }

BaseSurface fit(const std::vector<SurfaceSample>& samples, double outer, BaseKind kind,
                const BasePlanOptions& o, bool search_axis, BaseAxis& axis) {
  if (kind == BaseKind::kPlane) return BaseSurface::plane(outer);
  BaseFitOptions fo = o.fit;
  if (fo.rho_max <= 0)
    fo.rho_max = search_axis ? 1.3 * outer + o.minimax.max_shift : outer;
  const BaseSurface lsq = fit_base_least_squares(samples, fo);
  if (kind == BaseKind::kLeastSquares) return lsq;
  MinimaxBaseOptions mo = o.minimax;
  mo.search_axis = search_axis;
  const MinimaxBaseResult r = fit_base_minimax(samples, lsq, mo);
  axis = r.axis;
  return r.base;
}

}  // namespace

BasePlan plan_base_surface(const Surface& design, double inner, double outer,
                           const BasePlanOptions& o) {
  if (o.search_axis && o.kind != BaseKind::kMinimax)
    throw InputError("base", "the axis is searched by the minimax fit only (kind: minimax)");
  BasePlan plan;
  std::vector<SurfaceSample> samples =
      sample_aperture(design, inner, outer, o.radial_samples, o.angular_samples);
  plan.base = fit(samples, outer, o.kind, o, o.search_axis, plan.axis);
  if (o.search_axis) {
    // Mount the part on the axis: its crossing of the design goes to the origin.
    const Eigen::Vector3d t = plan.axis.direction();
    const HeightFieldHit hit = intersect_ray(design, plan.axis.point(), t, 0.0);
    if (hit.status != Status::kOk)
      throw InputError("base axis", "the searched axis does not cross the design surface",
                       "strategy.base_surface.search_axis");
    plan.axis_crossing = hit.point;
    plan.design_about_axis = std::make_unique<TransformedSurface>(
        std::make_unique<RaisedSurface>(design), hit.point.x(), hit.point.y(),
        Eigen::Matrix3d(Eigen::Quaterniond::FromTwoVectors(t, Eigen::Vector3d::UnitZ())));
    samples = sample_aperture(*plan.design_about_axis, inner, outer, o.radial_samples,
                              o.angular_samples);
    BaseAxis unused;
    plan.base = fit(samples, outer, o.kind, o, false, unused);
  }
  plan.quasi_revolution = measure_quasi_revolution(samples, plan.base);
  const QuasiRevolution& q = plan.quasi_revolution;
  if (o.angle_limit > 0 && q.max_angle > o.angle_limit) {
    const std::string message =
        "the design is not of quasi-revolution for its base: α reaches " + degrees(q.max_angle) +
        "°, above the limit " + degrees(o.angle_limit) + "°";
    const std::string where =
        "(x, y) = (" + fixed_text(q.where.x(), 6) + ", " + fixed_text(q.where.y(), 6) + ") mm";
    // The limit is the setting to look at first (raise it, or cut a traditional spiral).
    if (o.refuse_above_limit)
      throw InputError(where, message, "strategy.base_surface.max_normal_deviation_deg");
    plan.warnings.push_back(where + ": " + message);
  }
  return plan;
}

}  // namespace freeturn
