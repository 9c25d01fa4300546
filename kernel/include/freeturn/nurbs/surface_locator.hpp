#pragma once
// Closest points on a NURBS surface (point inversion) and ray–surface intersection.
//
// Cold queries start from a knot-aware grid of samples built once (a few per knot span in
// each direction): every local minimum of the sampled distance is a seed, and the best
// few are refined. Warm queries start from a previous answer, which keeps a spiral on its
// branch and costs a few Newton steps. Neither throws for an expected failure: the answer
// carries a Status.
//
// Point inversion is the damped Newton iteration of The NURBS Book §6.1 (Eq. 6.3-6.8) on
// f(u, v) = |S(u, v) − P|²/2, with Levenberg–Marquardt damping where the Hessian is not
// positive definite, an active set for the domain boundary (an edge solve in the free
// parameter when the answer lies on an edge), parameter wrapping on closed directions,
// and a cosine test that ignores a vanishing partial (a pole).

#include <vector>

#include "freeturn/core/status.hpp"
#include "freeturn/nurbs/surface.hpp"

namespace freeturn::nurbs {

struct SurfacePointResult {
  double u = 0, v = 0;
  Vector3d point = Vector3d::Zero();  // S(u, v)
  double distance = 0;                // |S(u, v) − P|
  Status status = Status::kNotConverged;
  int iterations = 0;
};

struct RayHit {
  double u = 0, v = 0;
  double t = 0;                       // signed distance along the unit ray direction
  Vector3d point = Vector3d::Zero();  // S(u, v)
  Status status = Status::kMissed;
  int iterations = 0;
};

struct LocatorOptions {
  double point_tolerance = 1e-12;   // mm: coincidence (stop when |S − P| is below)
  double cosine_tolerance = 1e-13;  // stop when |S_u·(S − P)| / (|S_u||S − P|) is below
  int max_iterations = 60;
  int samples_per_span = 4;  // cold-start grid density per knot span
  int cold_seeds = 8;        // local minima refined on a cold query (at most 16)
};

class SurfaceLocator {
 public:
  explicit SurfaceLocator(NurbsSurface surface, LocatorOptions options = {});

  const NurbsSurface& surface() const { return surface_; }
  bool closed_u() const { return closed_u_; }
  bool closed_v() const { return closed_v_; }

  // The closest point of the surface to p, from the sample grid.
  SurfacePointResult closest_point(const Vector3d& p) const;
  // The closest point near (u0, v0): a local answer, a few Newton steps.
  SurfacePointResult closest_point(const Vector3d& p, double u0, double v0) const;

  // The hit of the ray origin + t·direction (|direction| need not be 1) nearest the
  // origin (smallest |t|), from the sample grid; kMissed if the ray does not meet the
  // surface inside its domain.
  RayHit intersect_ray(const Vector3d& origin, const Vector3d& direction) const;
  // The hit near (u0, v0); kMissed if Newton leaves the domain without meeting it.
  RayHit intersect_ray(const Vector3d& origin, const Vector3d& direction, double u0,
                       double v0) const;

 private:
  // Grid local minima of a per-sample score, best first, at most `count`. Only the
  // samples of knot-span patches whose lower bound (lower_bound(box) ≤ score anywhere in
  // the patch's control-point box) can beat the best patch are scored at all.
  template <typename Score, typename LowerBound>
  void best_grid_minima(const Score& score, const LowerBound& lower_bound, int count,
                        std::vector<int>& out) const;
  void wrap_or_clamp(double& u, double& v) const;
  // On a degenerate edge (a pole) the partial along the edge vanishes and Newton cannot
  // see which way to leave it. If some direction out of the pole brings S closer to p,
  // moves (u, v) a little that way and returns true.
  bool leave_pole(const Vector3d& p, double& u, double& v) const;
  // Which edges collapse to a point: u = front, u = back, v = front, v = back.
  bool on_pole_edge(double u, double v) const;

  NurbsSurface surface_;
  LocatorOptions options_;
  bool closed_u_ = false, closed_v_ = false;
  bool pole_u_front_ = false, pole_u_back_ = false, pole_v_front_ = false, pole_v_back_ = false;
  std::vector<double> grid_u_, grid_v_;  // sample parameters
  std::vector<Vector3d> grid_points_;    // grid_u_.size() × grid_v_.size(), row-major
  // The largest diagonal of a grid cell: no surface point is farther than this from the
  // nearest sample of its cell, so a seed whose sample is farther than the best answer
  // plus this cannot lead to a better one.
  double cell_size_ = 0;
  // Knot-span patches: each covers per_span_u_ × per_span_v_ grid cells, and its control
  // points' box contains it (convex hull property, positive weights).
  int per_span_u_ = 0, per_span_v_ = 0, patches_u_ = 0, patches_v_ = 0;
  std::vector<Eigen::AlignedBox3d> patch_boxes_;
  // Rings of samples just off each pole, finer than the grid's first row: basins that
  // open between the pole and the grid's first row get seeds from them.
  struct PoleRing {
    std::vector<double> u, v;
    std::vector<Vector3d> points;
  };
  struct Pole {
    Vector3d point;
    double reach = 0;  // how far from the pole its rings (and the grid's first row) go
  };
  std::vector<Pole> poles_;
  std::vector<PoleRing> pole_rings_;
};

}  // namespace freeturn::nurbs
