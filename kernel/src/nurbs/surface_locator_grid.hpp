#pragma once
// Internal: the grid search shared by closest_point and intersect_ray.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "freeturn/nurbs/surface_locator.hpp"

namespace freeturn::nurbs {

template <typename Score, typename LowerBound>
void SurfaceLocator::best_grid_minima(const Score& score, const LowerBound& lower_bound, int count,
                                      std::vector<int>& out) const {
  // Reused per thread, so a cold query allocates nothing once the first has run. A
  // sample's value is valid only when its stamp is this query's: no clearing per query.
  thread_local std::vector<double> values, bounds;
  thread_local std::vector<unsigned> stamps;
  thread_local std::vector<int> scored;
  thread_local unsigned query = 0;
  const int nu = static_cast<int>(grid_u_.size()), nv = static_cast<int>(grid_v_.size());
  if (stamps.size() != grid_points_.size() || ++query == 0) {
    stamps.assign(grid_points_.size(), 0);
    values.resize(grid_points_.size());
    query = 1;
  }
  const auto value = [&](int k) { return stamps[k] == query ? values[k] : INFINITY; };

  // Branch and bound over the knot-span patches: the best patch's samples give an upper
  // bound on the answer; only patches whose box can come below it are sampled.
  bounds.resize(patch_boxes_.size());
  std::size_t best_patch = 0;
  for (std::size_t k = 0; k < patch_boxes_.size(); ++k) {
    bounds[k] = lower_bound(patch_boxes_[k]);
    if (bounds[k] < bounds[best_patch]) best_patch = k;
  }
  const auto score_patch = [&](std::size_t k) {
    const int a = static_cast<int>(k) / patches_v_, b = static_cast<int>(k) % patches_v_;
    double lowest = INFINITY;
    for (int i = a * per_span_u_; i <= (a + 1) * per_span_u_; ++i)
      for (int j = b * per_span_v_; j <= (b + 1) * per_span_v_; ++j) {
        const int index = i * nv + j;
        if (stamps[index] != query) {
          values[index] = score(grid_points_[index]);
          stamps[index] = query;
        }
        lowest = std::min(lowest, values[index]);
      }
    scored.push_back(static_cast<int>(k));
    return lowest;
  };
  scored.clear();
  const double upper = score_patch(best_patch);
  for (std::size_t k = 0; k < patch_boxes_.size(); ++k)
    if (k != best_patch && bounds[k] <= upper) score_patch(k);

  count = std::clamp(count, 1, 16);
  std::array<double, 16> best_values;
  out.clear();
  const auto neighbour = [&](int i, int n, bool closed) {
    // On a closed direction the first and last samples are the same point; step past it.
    if (i < 0) return closed ? n - 2 : -1;
    if (i >= n) return closed ? 1 : -1;
    return i;
  };
  // A pole is one point shared by a whole row of samples; the samples next to it are
  // judged against their ring only, so that every direction out of the pole that leads
  // into its own basin gets a seed.
  const auto pole_sample = [&](int i, int j) {
    return (pole_u_front_ && i == 0) || (pole_u_back_ && i == nu - 1) ||
           (pole_v_front_ && j == 0) || (pole_v_back_ && j == nv - 1);
  };
  for (int patch : scored) {
    const int a = patch / patches_v_, b = patch % patches_v_;
    for (int i = a * per_span_u_; i <= (a + 1) * per_span_u_; ++i) {
      for (int j = b * per_span_v_; j <= (b + 1) * per_span_v_; ++j) {
        const double s = values[i * nv + j];
        // Only a sample that would enter the list needs its neighbours checked.
        if (static_cast<int>(out.size()) == count && s >= best_values[count - 1]) continue;
        const bool at_pole = pole_sample(i, j);
        bool minimum = true;
        for (int di = -1; di <= 1 && minimum; ++di) {
          const int ii = neighbour(i + di, nu, closed_u_);
          if (ii < 0) continue;
          for (int dj = -1; dj <= 1; ++dj) {
            const int jj = neighbour(j + dj, nv, closed_v_);
            if (jj < 0 || (di == 0 && dj == 0)) continue;
            if (!at_pole && pole_sample(ii, jj)) continue;
            if (value(ii * nv + jj) < s) {
              minimum = false;
              break;
            }
          }
        }
        if (!minimum) continue;
        // Samples that are one point (a pole, a seam, a patch edge seen twice) are one seed.
        const Vector3d& q = grid_points_[i * nv + j];
        bool duplicate = false;
        for (int k : out) duplicate = duplicate || (grid_points_[k] - q).squaredNorm() == 0.0;
        if (duplicate) continue;
        // Insert into the sorted list of the best `count`.
        int pos = static_cast<int>(out.size());
        while (pos > 0 && best_values[pos - 1] > s) --pos;
        if (pos >= count) continue;
        if (static_cast<int>(out.size()) < count) out.push_back(0);
        for (int k = static_cast<int>(out.size()) - 1; k > pos; --k) {
          out[k] = out[k - 1];
          best_values[k] = best_values[k - 1];
        }
        out[pos] = i * nv + j;
        best_values[pos] = s;
      }
    }
  }
}

}  // namespace freeturn::nurbs
