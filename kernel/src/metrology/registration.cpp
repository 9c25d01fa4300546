// The registration's least squares (registration.hpp): dense normal equations of a few
// dozen unknowns, solved by Eigen's LDLT, in their own translation unit.
#include "freeturn/metrology/registration.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/nurbs/least_squares.hpp"
#include "freeturn/surface/zernike.hpp"

namespace freeturn {
namespace {

constexpr int kPose = 6;  // piston, tilt_x, tilt_y, decentre_x, decentre_y, clocking

Eigen::Matrix3d rotation(double tilt_x, double tilt_y, double clocking) {
  return (Eigen::AngleAxisd(clocking, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(tilt_y, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(tilt_x, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// The unknowns: the pose, then one a_j per fitted term.
struct Model {
  Eigen::VectorXd x;
  std::vector<int> terms;  // Noll j of each coefficient
  double rn = 1;

  Eigen::Vector3d to_design(const Eigen::Vector3d& p) const {
    return rotation(x[1], x[2], x[5]) * p + Eigen::Vector3d(x[3], x[4], x[0]);
  }
  std::unique_ptr<Zernike> error() const {
    std::vector<double> a(static_cast<std::size_t>(terms.empty() ? 0 : terms.back()), 0.0);
    for (std::size_t k = 0; k < terms.size(); ++k)
      a[static_cast<std::size_t>(terms[k] - 1)] = x[kPose + static_cast<Eigen::Index>(k)];
    return std::make_unique<Zernike>(0, 0, std::array<double, 9>{}, rn, a);
  }
};

}  // namespace

namespace {

// Whether the points tell every Zernike term from the others: the terms' block of JᵀJ
// (their values at the points, Σ Z_i Z_j), scaled to a unit diagonal, has a pivot of its
// LDLᵀ factorisation near 0 where one term is a combination of the others there. The
// terms alone: a rotationally symmetric design leaves clocking undetermined, a sphere
// decentre against tilt, and the damping keeps those still. The terms are the design's
// correction, which the planner then follows everywhere in the aperture: 1000 copies of
// one point had fitted a correction that tilted the design 85° from the spindle axis.
// Returns the Noll index of a term the points leave undetermined, or 0.
int undetermined_term(const Eigen::MatrixXd& jtj, const std::vector<int>& terms) {
  const Eigen::Index count = static_cast<Eigen::Index>(terms.size());
  if (count == 0) return 0;
  Eigen::MatrixXd block = jtj.block(kPose, kPose, count, count).selfadjointView<Eigen::Lower>();
  Eigen::VectorXd scale(count);
  for (Eigen::Index k = 0; k < count; ++k) {
    if (!(block(k, k) > 0)) return terms[static_cast<std::size_t>(k)];  // zero at every point
    scale[k] = 1 / std::sqrt(block(k, k));
  }
  block = scale.asDiagonal() * block * scale.asDiagonal();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(block);
  // D's k-th entry belongs to the term the pivoting moved to place k.
  Eigen::VectorXi order = Eigen::VectorXi::LinSpaced(count, 0, static_cast<int>(count) - 1);
  order = ldlt.transpositionsP() * order;
  constexpr double kDetermined = 1e-9;
  for (Eigen::Index k = 0; k < count; ++k)
    if (!(ldlt.vectorD()[k] > kDetermined)) return terms[static_cast<std::size_t>(order[k])];
  return 0;
}

// The B-spline's parameter of a coordinate: its square spans [−half, half] in x and in y.
double bspline_parameter(double coordinate, double half) {
  return std::clamp((coordinate + half) / (2 * half), 0.0, 1.0);
}

}  // namespace

double bspline_height(const nurbs::NurbsSurface& bspline, double normalization_radius, double x,
                      double y) {
  const double half = kBsplineReach * normalization_radius;
  return bspline.point(bspline_parameter(x, half), bspline_parameter(y, half)).z();
}

Registration register_measurement(const Surface& design, const Measurement& m,
                                  const RegistrationOptions& o, const std::string& where) {
  Model model;
  model.rn = o.normalization_radius;
  for (int j = 1; j <= o.zernike_terms; ++j) {
    if (j == 1 && o.piston) continue;
    if ((j == 2 || j == 3) && o.tilt) continue;
    if (o.profile && noll_to_nm(j).m != 0) continue;
    model.terms.push_back(j);
  }
  const int unknowns = kPose + static_cast<int>(model.terms.size());
  const bool free[kPose] = {o.piston,   o.tilt && !o.profile,     o.tilt,
                            o.decentre, o.decentre && !o.profile, o.clocking && !o.profile};
  model.x = Eigen::VectorXd::Zero(unknowns);
  // One Zernike per term: its value at a point is that term's column of the Jacobian.
  std::vector<std::unique_ptr<Zernike>> basis;
  for (const int j : model.terms) {
    std::vector<double> unit(static_cast<std::size_t>(j), 0.0);
    unit.back() = 1;
    basis.push_back(std::make_unique<Zernike>(0, 0, std::array<double, 9>{}, model.rn, unit));
  }
  const std::size_t n = m.points.size();
  std::vector<char> excluded(n, 0);
  const double width = o.outer_radius - o.inner_radius;

  // Σ r², JᵀJ and Jᵀr over the points used at `model`; false when too few are inside.
  Eigen::MatrixXd jtj(unknowns, unknowns);
  Eigen::VectorXd jtr(unknowns), row(unknowns);
  std::vector<double> residual(n, 0.0);
  std::vector<char> inside(n, 0);
  const auto evaluate = [&](const Model& at, bool with_jacobian, long& used) {
    const std::unique_ptr<Zernike> error = at.error();
    const Eigen::Matrix3d r = rotation(at.x[1], at.x[2], at.x[5]);
    // Derivatives of R·p in the three angles, by central differences of R (exact enough:
    // the angles are small and the step is 1e-7 rad).
    const double h = 1e-7;
    const Eigen::Matrix3d d_tx = (rotation(at.x[1] + h, at.x[2], at.x[5]) - rotation(at.x[1] - h, at.x[2], at.x[5])) / (2 * h);
    const Eigen::Matrix3d d_ty = (rotation(at.x[1], at.x[2] + h, at.x[5]) - rotation(at.x[1], at.x[2] - h, at.x[5])) / (2 * h);
    const Eigen::Matrix3d d_c = (rotation(at.x[1], at.x[2], at.x[5] + h) - rotation(at.x[1], at.x[2], at.x[5] - h)) / (2 * h);
    double cost = 0;
    used = 0;
    if (with_jacobian) jtj.setZero(), jtr.setZero();
    for (std::size_t i = 0; i < n; ++i) {
      inside[i] = 0;
      if (excluded[i]) continue;
      const Eigen::Vector3d& p = m.points[i];
      const Eigen::Vector3d q = r * p + Eigen::Vector3d(at.x[3], at.x[4], at.x[0]);
      const double rho = std::hypot(q.x(), q.y());
      if (rho < o.inner_radius || rho > o.outer_radius) continue;
      double z, zx, zy, e, ex, ey;
      design.sag_gradient(q.x(), q.y(), z, zx, zy);
      error->sag_gradient(q.x(), q.y(), e, ex, ey);
      if (!std::isfinite(z)) continue;
      inside[i] = 1;
      ++used;
      const double res = q.z() - z - e;
      residual[i] = res;
      cost += res * res;
      if (!with_jacobian) continue;
      // ∂r/∂q = (−(zx + ex), −(zy + ey), 1).
      const Eigen::Vector3d g(-(zx + ex), -(zy + ey), 1.0);
      row.setZero();
      row[0] = 1;
      row[1] = g.dot(d_tx * p);
      row[2] = g.dot(d_ty * p);
      row[3] = g.x();
      row[4] = g.y();
      row[5] = g.dot(d_c * p);
      for (std::size_t k = 0; k < basis.size(); ++k)
        row[kPose + static_cast<Eigen::Index>(k)] = -basis[k]->sag(q.x(), q.y());
      for (int k = 0; k < kPose; ++k)
        if (!free[k]) row[k] = 0;
      jtj.selfadjointView<Eigen::Lower>().rankUpdate(row);
      jtr += row * res;
    }
    return cost;
  };

  // The B-spline part (RegistrationOptions::bspline_control): what the Zernike terms leave,
  // fitted at the points used, where they lie on the design, over a square that reaches
  // kBsplineReach · R_n: the planner and the checks evaluate the corrected design past the
  // aperture's edge (a projection along a tilted base normal lands beyond it, the nose's
  // edge overhangs it), where a square of [−R_n, R_n]² had no value and a space spiral
  // stopped at the aperture's edge. The ring beyond the data is filled by the smoothing.
  const double half = kBsplineReach * model.rn;
  const auto bspline_at = [&model](const nurbs::NurbsSurface& b, const Eigen::Vector3d& q) {
    return bspline_height(b, model.rn, q.x(), q.y());
  };
  const auto fit_bspline = [&]() -> std::optional<nurbs::NurbsSurface> {
    if (o.bspline_control <= 0) return std::nullopt;
    std::vector<Eigen::Vector3d> points;
    std::vector<double> u, v;
    for (std::size_t i = 0; i < n; ++i) {
      if (!inside[i]) continue;
      const Eigen::Vector3d q = model.to_design(m.points[i]);
      points.emplace_back(q.x(), q.y(), residual[i]);
      u.push_back(bspline_parameter(q.x(), half));
      v.push_back(bspline_parameter(q.y(), half));
    }
    // bspline_control per side over the aperture's diameter: the same knot spacing over
    // the wider square.
    const int c = 3 + static_cast<int>(std::ceil(kBsplineReach * (o.bspline_control - 3)));
    nurbs::SurfaceFitOptions fo;
    fo.count_u = fo.count_v = c;
    for (int k = 0; k <= 3; ++k) fo.knots_u.push_back(0.0);
    for (int k = 1; k < c - 3; ++k) fo.knots_u.push_back(static_cast<double>(k) / (c - 3));
    for (int k = 0; k <= 3; ++k) fo.knots_u.push_back(1.0);
    fo.knots_v = fo.knots_u;
    fo.smoothing = o.bspline_smoothing;
    try {
      const nurbs::NurbsSurface fitted = nurbs::fit_surface_scattered(points, u, v, fo).surface;
      // x and y are affine in u and v (the thin-plate energy and the data both hold them
      // so); the solve leaves them so only to rounding, 1e-11 mm in the square's corners
      // where no data lies. Placed exactly, the height field needs no inversion.
      std::vector<Eigen::Vector4d> pw(fitted.homogeneous_points());
      for (int i = 0; i < c; ++i)
        for (int j = 0; j < c; ++j) {
          Eigen::Vector4d& p = pw[static_cast<std::size_t>(i * c + j)];
          p.x() = -half + 2 * half * fitted.knots_u().greville(i);
          p.y() = -half + 2 * half * fitted.knots_v().greville(j);
        }
      return nurbs::NurbsSurface(fitted.knots_u(), fitted.knots_v(), std::move(pw));
    } catch (const InputError& e) {
      if (e.where() == "smoothing") throw;  // the caller knows where the weight was set
      throw InputError(where, "the B-spline fit of the error: " + e.problem() +
                                  " (fewer control points, or smoothing)");
    }
  };
  std::optional<nurbs::NurbsSurface> bspline;

  Registration out;
  long used = 0;
  int iterations = 0;
  for (int round = 0; round < 6; ++round) {
    double lambda = 1e-6;
    double cost = evaluate(model, true, used);
    // Heights whose squares overflow (1e300 µm) leave no step to compare: no surface's.
    if (!std::isfinite(cost))
      throw InputError(where,
                       "the measured heights are too large to be a surface's (their "
                       "sum of squares overflows): is the file in these units?");
    if (used < std::max<long>(3L * unknowns, 30))
      throw InputError(where, std::to_string(used) + " valid points fall inside the aperture (" +
                                  fixed_text(o.inner_radius, 3) + " – " + fixed_text(o.outer_radius, 3) +
                                  " mm) once registered: too few to register and fit " +
                                  std::to_string(unknowns) + " unknowns (is the measurement "
                                  "outside the aperture, or in other units?)");
    if (const int term = undetermined_term(jtj, model.terms))
      throw InputError(where, "the " + std::to_string(used) +
                                  " valid points inside the aperture cannot tell Zernike term " +
                                  std::to_string(term) +
                                  " from the others (they cover too little "
                                  "of it, or lie on a line or a ring): fewer terms, or a "
                                  "measurement over the aperture");
    for (int it = 0; it < o.max_iterations; ++it, ++iterations) {
      const Eigen::MatrixXd full = jtj.selfadjointView<Eigen::Lower>();
      bool improved = false;
      for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
        Eigen::MatrixXd a = full;
        for (int k = 0; k < unknowns; ++k) {
          const bool fixed = k < kPose && !free[k];
          a(k, k) += fixed ? 1.0 : lambda * std::max(full(k, k), 1e-12);
        }
        const Eigen::VectorXd step = a.ldlt().solve(-jtr);
        Model trial = model;
        trial.x += step;
        long trial_used = 0;
        const double trial_cost = evaluate(trial, false, trial_used);
        if (std::isfinite(trial_cost) && trial_cost <= cost && trial_used >= used * 9 / 10) {
          const bool small = step.head(kPose).cwiseAbs().maxCoeff() < 1e-12 &&
                             (step.size() == kPose || step.tail(step.size() - kPose).cwiseAbs().maxCoeff() < 1e-15);
          const double before = cost;
          model = trial;
          lambda = std::max(lambda / 10, 1e-12);
          improved = true;
          cost = evaluate(model, true, used);
          // Converged: the pose no longer moves, or the cost no longer falls.
          if (small || before - cost <= 1e-12 * before) it = o.max_iterations;
        } else {
          lambda *= 10;
        }
      }
      if (!improved) break;  // no step lowers the cost: the minimum, to the damping's resolution
      if (std::abs(model.x[3]) > width || std::abs(model.x[4]) > width || std::abs(model.x[1]) > 0.5 ||
          std::abs(model.x[2]) > 0.5)
        throw InputError(where, "the registration diverges (decentre " +
                                    significant_text(std::hypot(model.x[3], model.x[4]), 3) +
                                    " mm, tilt " + significant_text(std::hypot(model.x[1], model.x[2]), 3) +
                                    " rad): is the measurement of this part, in these units?");
    }
    // The residuals of the model kept: the last evaluation may have been of a trial step
    // the loop refused, whose points can all lie elsewhere.
    evaluate(model, false, used);
    // Outliers against this fit (the B-spline's too, so that a bump it holds is not taken
    // for outliers), by a robust σ of the points it used; every point is judged anew (a
    // point the first, spike-pulled fit dropped comes back once the fit settles).
    bspline = fit_bspline();
    const auto left = [&](std::size_t i) {
      return bspline ? residual[i] - bspline_at(*bspline, model.to_design(m.points[i])) : residual[i];
    };
    std::vector<double> sorted;
    for (std::size_t i = 0; i < n; ++i)
      if (inside[i]) sorted.push_back(left(i));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (double& v : sorted) v = std::abs(v - median);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double sigma = 1.4826 * sorted[sorted.size() / 2];
    std::fill(excluded.begin(), excluded.end(), 0);
    long dropped = 0;
    evaluate(model, false, used);  // every point's residual, none excluded
    for (std::size_t i = 0; i < n; ++i)
      if (inside[i] && sigma > 0 && std::abs(left(i) - median) > o.outlier_sigmas * sigma) {
        excluded[i] = 1;
        ++dropped;
      }
    const bool settled = dropped == out.outliers;
    out.outliers = dropped;
    if (dropped == 0 || settled) break;
  }
  evaluate(model, false, used);
  bspline = fit_bspline();
  out.piston = model.x[0];
  out.tilt_x = model.x[1];
  out.tilt_y = model.x[2];
  out.decentre_x = model.x[3];
  out.decentre_y = model.x[4];
  out.clocking = model.x[5];
  out.normalization_radius = model.rn;
  out.zernike.assign(static_cast<std::size_t>(std::max(o.zernike_terms, 0)), 0.0);
  for (std::size_t k = 0; k < model.terms.size(); ++k)
    out.zernike[static_cast<std::size_t>(model.terms[k] - 1)] = model.x[kPose + static_cast<Eigen::Index>(k)];
  out.used = used;
  out.iterations = iterations;
  const std::unique_ptr<Zernike> error = model.error();
  double fit_sq = 0, e_sq = 0, e_max = -1e300, e_min = 1e300;
  long outside = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!inside[i]) {
      if (!excluded[i]) ++outside;
      continue;
    }
    const Eigen::Vector3d q = model.to_design(m.points[i]);
    const double e = residual[i] + error->sag(q.x(), q.y());
    fit_sq += residual[i] * residual[i];
    e_sq += e * e;
    e_max = std::max(e_max, e), e_min = std::min(e_min, e);
  }
  out.outside = outside;
  if (bspline) {
    double b_sq = 0;
    fit_sq = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!inside[i]) continue;
      const Eigen::Vector3d q = model.to_design(m.points[i]);
      const double b = bspline_at(*bspline, q);
      b_sq += b * b;
      fit_sq += (residual[i] - b) * (residual[i] - b);
    }
    out.bspline_rms = std::sqrt(b_sq / static_cast<double>(std::max(used, 1L)));
    out.bspline = std::move(bspline);
    out.bspline_control = o.bspline_control;
  }
  out.fit_rms = std::sqrt(fit_sq / static_cast<double>(std::max(used, 1L)));
  out.measured_rms = std::sqrt(e_sq / static_cast<double>(std::max(used, 1L)));
  out.measured_pv = used > 0 ? e_max - e_min : 0.0;
  return out;
}

}  // namespace freeturn
