#pragma once
// Internal: the grid search shared by closest_point and intersect_ray.

#include <algorithm>
#include <array>
#include <vector>

#include "freeturn/nurbs/surface_locator.hpp"

namespace freeturn::nurbs {

template <typename Score>
void SurfaceLocator::best_grid_minima(const Score& score, int count, std::vector<int>& out) const {
  // Reused per thread: a cold query allocates nothing once the first one has run.
  thread_local std::vector<double> values;
  const int nu = static_cast<int>(grid_u_.size()), nv = static_cast<int>(grid_v_.size());
  values.resize(grid_points_.size());
  for (std::size_t k = 0; k < grid_points_.size(); ++k) values[k] = score(grid_points_[k]);

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
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double s = values[i * nv + j];
      const bool at_pole = pole_sample(i, j);
      bool minimum = true;
      for (int di = -1; di <= 1 && minimum; ++di) {
        const int ii = neighbour(i + di, nu, closed_u_);
        if (ii < 0) continue;
        for (int dj = -1; dj <= 1; ++dj) {
          const int jj = neighbour(j + dj, nv, closed_v_);
          if (jj < 0 || (di == 0 && dj == 0)) continue;
          if (!at_pole && pole_sample(ii, jj)) continue;
          if (values[ii * nv + jj] < s) {
            minimum = false;
            break;
          }
        }
      }
      if (!minimum) continue;
      // Samples that are one point (a pole, a seam) are one seed.
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

}  // namespace freeturn::nurbs
