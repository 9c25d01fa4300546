#include "freeturn/path/minimax_base_fit.hpp"

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <algorithm>
#include <cmath>
#include <mutex>

#include "freeturn/path/base_axis_fit.hpp"
#include "revolution_terms.hpp"

namespace freeturn {
namespace {

using Ipopt::Index;
using Ipopt::Number;

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
                 const BaseAxis& start_axis, const MinimaxBaseOptions& options)
      : samples_(samples), options_(options), start_axis_(start_axis),
        slope_(start.degree(), start.knots()) {
    const std::vector<double>& c = start.coefficients();
    start_.assign(c.begin() + 2, c.end());
    const double c0 = c[0];
    for (double& v : start_) v -= c0;
    free_coefficients_ = static_cast<int>(start_.size());
    axis_offset_ = free_coefficients_;
    epigraph_ = axis_offset_ + (options_.search_axis ? 4 : 0);
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
    if (options_.search_axis) {
      x[axis_offset_] = start_axis_.tilt_x;
      x[axis_offset_ + 1] = start_axis_.tilt_y;
      x[axis_offset_ + 2] = start_axis_.shift_x;
      x[axis_offset_ + 3] = start_axis_.shift_y;
    }
    double worst = 0;
    for (std::size_t k = 0; k < samples_.size(); ++k)
      worst = std::max(worst, 1 - cosine(k, x, nullptr));
    x[epigraph_] = worst;  // a feasible start
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
  int epigraph() const { return epigraph_; }
  int axis_offset() const { return axis_offset_; }

  // cos α_k at x; with `gradient`, adds ∂cos α_k/∂x into it.
  double cosine(std::size_t k, const Number* x, Number* gradient) {
    const detail::RevolutionTerms t = detail::revolution_terms(
        samples_[k], options_.search_axis ? x + axis_offset_ : nullptr);
    slope_.evaluate(t.rho.value(), x);
    const detail::AxisAd hp(slope_.slope, slope_.curvature * t.rho.derivatives());
    const detail::AxisAd g = (t.n_h - t.n_rho * hp) / sqrt(1.0 + hp * hp);
    if (gradient != nullptr) {
      const double h = hp.value();
      // ∂cos α/∂H' = (−n_ρ − n_h H')/(1 + H'²)^{3/2}.
      const double dg_dslope = (-t.n_rho.value() - t.n_h.value() * h) / std::pow(1.0 + h * h, 1.5);
      for (int b = 0; b < slope_.count(); ++b) {
        const int i = slope_.first() + b;
        if (i >= 2) gradient[i - 2] += dg_dslope * slope_.basis_slope(b);
      }
      if (options_.search_axis)
        for (int a = 0; a < 4; ++a) gradient[axis_offset_ + a] += g.derivatives()(a);
    }
    return g.value();
  }

 private:
  const std::vector<SurfaceSample>& samples_;
  MinimaxBaseOptions options_;
  BaseAxis start_axis_;
  detail::BaseSlope slope_;
  std::vector<double> start_;
  int free_coefficients_ = 0, axis_offset_ = 0, epigraph_ = 0;
  std::vector<double> solution_;
  bool solved_ = false;
};

}  // namespace

MinimaxBaseResult fit_base_minimax(const std::vector<SurfaceSample>& samples,
                                   const BaseSurface& start, const MinimaxBaseOptions& options) {
  MinimaxBaseResult result{start, {}};
  result.start_max_angle = measure_quasi_revolution(samples, start).max_angle;
  BaseSurface first = start;
  BaseAxis first_axis;
  result.least_squares_max_angle = result.start_max_angle;
  if (options.search_axis) {
    const BaseAxisFit lsq = fit_base_and_axis_least_squares(samples, start);
    first = lsq.base;
    first_axis = lsq.axis;
    result.least_squares_max_angle = lsq.max_angle;
    // A surface of revolution about some axis: the least-squares fit has found it, and no
    // maximum can be lower.
    if (lsq.max_angle < 1e-9) {
      result.base = lsq.base;
      result.axis = lsq.axis;
      result.max_angle = lsq.max_angle;
      result.status = lsq.status;
      return result;
    }
  }
  Ipopt::SmartPtr<MinimaxProblem> problem = new MinimaxProblem(samples, first, first_axis, options);
  Ipopt::ApplicationReturnStatus status = Ipopt::Internal_Error;
  {
    const std::lock_guard<std::mutex> lock(ipopt_mutex());
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    app->Options()->SetIntegerValue("print_level", options.verbose ? 5 : 0);
    app->Options()->SetStringValue("sb", "yes");
    app->Options()->SetStringValue("hessian_approximation", "limited-memory");
    app->Options()->SetNumericValue("tol", 1e-10);
    app->Options()->SetNumericValue("acceptable_tol", 1e-8);
    app->Options()->SetIntegerValue("acceptable_iter", 5);
    app->Options()->SetIntegerValue("max_iter", options.max_iterations);
    app->Options()->SetStringValue("mu_strategy", "adaptive");
    status = app->Initialize("");  // "": no ipopt.opt from the working directory
    if (status == Ipopt::Solve_Succeeded) {
      status = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(problem)));
      if (IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
    }
  }
  // The better of the start and the optimiser's answer (it may stop early on a flat
  // minimax), never worse than the start.
  result.base = first;
  result.axis = first_axis;
  result.max_angle = measure_quasi_revolution(samples, first, first_axis).max_angle;
  if (!problem->solution().empty()) {
    const std::vector<double>& x = problem->solution();
    std::vector<double> c(start.coefficients().size(), 0.0);
    for (std::size_t i = 2; i < c.size(); ++i) c[i] = x[i - 2];
    BaseAxis axis = first_axis;
    if (options.search_axis) {
      const int a = problem->axis_offset();
      axis = {x[a], x[a + 1], x[a + 2], x[a + 3]};
    }
    const BaseSurface base =
        with_height_offset(samples, BaseSurface(start.degree(), start.knots(), c), axis);
    const double max_angle = measure_quasi_revolution(samples, base, axis).max_angle;
    if (max_angle <= result.max_angle) {
      result.base = base;
      result.axis = axis;
      result.max_angle = max_angle;
    }
  }
  result.status = problem->solved() || status == Ipopt::Solved_To_Acceptable_Level
                      ? Status::kOk
                      : Status::kNotConverged;
  return result;
}

}  // namespace freeturn
