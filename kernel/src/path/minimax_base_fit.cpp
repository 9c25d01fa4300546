#include "freeturn/path/minimax_base_fit.hpp"

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <unsupported/Eigen/AutoDiff>

#include "freeturn/nurbs/basis.hpp"
#include "freeturn/nurbs/knot_vector.hpp"

namespace freeturn {
namespace {

using Ipopt::Index;
using Ipopt::Number;
using Ad = Eigen::AutoDiffScalar<Eigen::Vector4d>;

// Ipopt with MUMPS is not thread-safe: one lock for the whole application lifetime.
std::mutex& ipopt_mutex() {
  static std::mutex m;
  return m;
}

// Variables: c_2 … c_{n−1} (c_0 = c_1 = 0: the offset does not change a normal, and
// c_1 = c_0 keeps H'(0) = 0), then [tilt_x, tilt_y, shift_x, shift_y] when searching the
// axis, then A. Constraints: cos α_k + A ≥ 1.
class MinimaxProblem final : public Ipopt::TNLP {
 public:
  MinimaxProblem(const std::vector<SurfaceSample>& samples, const BaseSurface& start,
                 const MinimaxBaseOptions& options)
      : samples_(samples), options_(options), degree_(start.degree()),
        knots_(start.knots()), kv_(start.degree(), start.knots()),
        coefficient_count_(static_cast<int>(start.coefficients().size())) {
    const std::vector<double>& c = start.coefficients();
    start_.assign(c.begin() + 2, c.end());
    const double c0 = c[0];
    for (double& v : start_) v -= c0;
    free_coefficients_ = static_cast<int>(start_.size());
    axis_offset_ = free_coefficients_;
    epigraph_ = axis_offset_ + (options_.search_axis ? 4 : 0);
    ders_.resize(static_cast<std::size_t>(3 * (degree_ + 1)));
    work_.resize(nurbs::basis_derivatives_work_size(degree_));
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = epigraph_ + 1;
    m = static_cast<Index>(samples_.size());
    nnz_jac_g = n * m;  // dense rows: a row touches at most p+1 coefficients, but n is small
    nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = -1e19;
      x_u[i] = 1e19;
    }
    if (options_.search_axis) {
      for (int k = 0; k < 2; ++k) {
        x_l[axis_offset_ + k] = -options_.max_tilt;
        x_u[axis_offset_ + k] = options_.max_tilt;
        x_l[axis_offset_ + 2 + k] = -options_.max_shift;
        x_u[axis_offset_ + 2 + k] = options_.max_shift;
      }
    }
    x_l[epigraph_] = 0;
    for (Index k = 0; k < m; ++k) {
      g_l[k] = 1;
      g_u[k] = 1e19;
    }
    return true;
  }

  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    std::fill(x, x + n, 0.0);
    std::copy(start_.begin(), start_.end(), x);
    double worst = 0;
    for (std::size_t k = 0; k < samples_.size(); ++k)
      worst = std::max(worst, 1 - cosine(k, x, nullptr));
    x[epigraph_] = worst;
    start_max_ = worst;
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& f) override {
    f = x[epigraph_];
    return true;
  }
  bool eval_grad_f(Index n, const Number*, bool, Number* grad) override {
    std::fill(grad, grad + n, 0.0);
    grad[epigraph_] = 1;
    return true;
  }
  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    for (Index k = 0; k < m; ++k)
      g[k] = cosine(static_cast<std::size_t>(k), x, nullptr) + x[epigraph_];
    return true;
  }
  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* rows, Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      for (Index k = 0; k < m; ++k)
        for (Index i = 0; i < n; ++i) {
          rows[k * n + i] = k;
          cols[k * n + i] = i;
        }
      return true;
    }
    for (Index k = 0; k < m; ++k) {
      Number* row = values + k * n;
      std::fill(row, row + n, 0.0);
      cosine(static_cast<std::size_t>(k), x, row);
      row[epigraph_] = 1;
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.assign(x, x + n);
    solved_ = status == Ipopt::SUCCESS || status == Ipopt::STOP_AT_ACCEPTABLE_POINT;
  }

  const std::vector<double>& solution() const { return solution_; }
  bool solved() const { return solved_; }
  double start_max() const { return start_max_; }
  int epigraph() const { return epigraph_; }
  int axis_offset() const { return axis_offset_; }

  // cos α_k at x; with `gradient`, adds ∂cos α_k/∂x into it.
  double cosine(std::size_t k, const Number* x, Number* gradient) {
    const SurfaceSample& s = samples_[k];
    const Eigen::Vector3d& n = s.normal;
    Ad rho, nh, nrho;
    if (options_.search_axis) {
      const Ad tx(x[axis_offset_], 4, 0), ty(x[axis_offset_ + 1], 4, 1);
      const Ad ox(x[axis_offset_ + 2], 4, 2), oy(x[axis_offset_ + 3], 4, 3);
      // t = R_y(ty) R_x(tx) e_z.
      const Ad t0 = cos(tx) * sin(ty), t1 = -sin(tx), t2 = cos(tx) * cos(ty);
      const Ad d0 = s.point.x() - ox, d1 = s.point.y() - oy;
      const double d2 = s.point.z();
      const Ad h = d0 * t0 + d1 * t1 + d2 * t2;
      const Ad w0 = d0 - h * t0, w1 = d1 - h * t1, w2 = d2 - h * t2;
      rho = sqrt(w0 * w0 + w1 * w1 + w2 * w2);
      nh = n.x() * t0 + n.y() * t1 + n.z() * t2;
      nrho = rho.value() > 1e-12 ? Ad((n.x() * w0 + n.y() * w1 + n.z() * w2) / rho) : Ad(0.0);
    } else {
      const double r = s.point.head<2>().norm();
      rho = Ad(r, Eigen::Vector4d::Zero());
      nh = Ad(n.z(), Eigen::Vector4d::Zero());
      nrho = Ad(r > 1e-12 ? n.head<2>().dot(s.point.head<2>()) / r : 0.0, Eigen::Vector4d::Zero());
    }
    // H'(ρ) and H''(ρ) from the basis derivatives at ρ (clamped to the domain).
    const double r = std::clamp(rho.value(), knots_.front(), knots_.back());
    const int span = kv_.find_span(r);
    nurbs::basis_function_derivatives(span, r, degree_, 2, knots_.data(), ders_.data(), work_.data());
    const int q = degree_ + 1;
    double h1 = 0, h2 = 0;
    for (int j = 0; j < q; ++j) {
      const int i = span - degree_ + j;
      const double c = i <= 1 ? 0.0 : x[i - 2];
      h1 += c * ders_[static_cast<std::size_t>(q + j)];
      h2 += c * ders_[static_cast<std::size_t>(2 * q + j)];
    }
    const Ad slope(h1, h2 * rho.derivatives());
    const Ad g = (nh - nrho * slope) / sqrt(1.0 + slope * slope);
    if (gradient != nullptr) {
      const double sv = slope.value();
      const double dg_dslope =
          (-nrho.value() - nh.value() * sv) / std::pow(1.0 + sv * sv, 1.5);
      for (int j = 0; j < q; ++j) {
        const int i = span - degree_ + j;
        if (i >= 2) gradient[i - 2] += dg_dslope * ders_[static_cast<std::size_t>(q + j)];
      }
      if (options_.search_axis)
        for (int a = 0; a < 4; ++a) gradient[axis_offset_ + a] += g.derivatives()(a);
    }
    return g.value();
  }

 private:
  const std::vector<SurfaceSample>& samples_;
  MinimaxBaseOptions options_;
  int degree_;
  std::vector<double> knots_;
  nurbs::KnotVector kv_;
  int coefficient_count_;
  std::vector<double> start_;
  int free_coefficients_ = 0, axis_offset_ = 0, epigraph_ = 0;
  std::vector<double> ders_, work_, solution_;
  bool solved_ = false;
  double start_max_ = 0;
};

}  // namespace

MinimaxBaseResult fit_base_minimax(const std::vector<SurfaceSample>& samples,
                                   const BaseSurface& start, const MinimaxBaseOptions& options) {
  Ipopt::SmartPtr<MinimaxProblem> problem = new MinimaxProblem(samples, start, options);
  Ipopt::ApplicationReturnStatus status;
  int iterations = 0;
  {
    const std::lock_guard<std::mutex> lock(ipopt_mutex());
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetIntegerValue("print_level", options.verbose ? 5 : 0);
    app->Options()->SetStringValue("sb", "yes");
    app->Options()->SetStringValue("hessian_approximation", "limited-memory");
    app->Options()->SetNumericValue("tol", 1e-12);
    app->Options()->SetNumericValue("acceptable_tol", 1e-9);
    app->Options()->SetIntegerValue("max_iter", options.max_iterations);
    app->Options()->SetStringValue("mu_strategy", "adaptive");
    status = app->Initialize("");  // "": no ipopt.opt from the working directory
    if (status == Ipopt::Solve_Succeeded) {
      status = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(problem)));
      if (IsValid(app->Statistics())) iterations = app->Statistics()->IterationCount();
    }
  }
  MinimaxBaseResult result{start};
  result.start_max_angle = std::acos(std::clamp(1.0 - problem->start_max(), -1.0, 1.0));
  result.iterations = iterations;
  result.max_angle = result.start_max_angle;
  if (problem->solution().empty()) return result;
  const std::vector<double>& x = problem->solution();
  std::vector<double> c(start.coefficients().size(), 0.0);
  for (std::size_t i = 2; i < c.size(); ++i) c[i] = x[i - 2];
  if (options.search_axis) {
    const int a = problem->axis_offset();
    result.tilt_x = x[a];
    result.tilt_y = x[a + 1];
    result.axis_direction = Eigen::Vector3d(std::cos(x[a]) * std::sin(x[a + 1]), -std::sin(x[a]),
                                            std::cos(x[a]) * std::cos(x[a + 1]));
    result.axis_point = Eigen::Vector3d(x[a + 2], x[a + 3], 0);
  }
  // The offset c_0 = c_1 is free for the angles; set it to the samples' mean height
  // residual so the base passes through the part.
  double offset = 0;
  {
    const BaseSurface shape(start.degree(), start.knots(), c);
    for (const SurfaceSample& s : samples) {
      const Eigen::Vector3d d = s.point - result.axis_point;
      const double h = d.dot(result.axis_direction);
      const double rho = (d - h * result.axis_direction).norm();
      offset += h - shape.at_radius(rho).h;
    }
    offset /= static_cast<double>(samples.size());
  }
  for (double& v : c) v += offset;
  result.base = BaseSurface(start.degree(), start.knots(), c);
  std::vector<double> probe(x);
  double worst = 0;
  for (std::size_t k = 0; k < samples.size(); ++k)
    worst = std::max(worst, 1 - problem->cosine(k, probe.data(), nullptr));
  result.max_angle = std::acos(std::clamp(1.0 - worst, -1.0, 1.0));
  result.status = problem->solved() || status == Ipopt::Solved_To_Acceptable_Level
                      ? Status::kOk
                      : Status::kNotConverged;
  return result;
}

}  // namespace freeturn
