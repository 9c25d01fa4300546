#include "freeturn/tool/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace freeturn {
namespace {

constexpr int kRadii = 129, kAngles = 360, kRefined = 8;

double sag_at(const Surface& s, double r, double theta) {
  double z = 0, zx = 0, zy = 0;
  s.sag_gradient(r * std::cos(theta), r * std::sin(theta), z, zx, zy);
  return std::isfinite(z) ? z : -std::numeric_limits<double>::infinity();
}

}  // namespace

double highest_sag(const Surface& surface, double inner_radius, double outer_radius) {
  struct Sample {
    double z, r, theta;
  };
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(kRadii) * kAngles);
  const double span = outer_radius - inner_radius;
  for (int i = 0; i < kRadii; ++i) {
    const double r = inner_radius + span * i / (kRadii - 1);
    const int angles = r == 0 ? 1 : kAngles;
    for (int j = 0; j < angles; ++j) {
      const double theta = 2 * std::numbers::pi * j / kAngles;
      samples.push_back({sag_at(surface, r, theta), r, theta});
    }
  }
  const auto best = samples.begin() + std::min<std::ptrdiff_t>(kRefined, std::ssize(samples));
  std::partial_sort(samples.begin(), best, samples.end(),
                    [](const Sample& a, const Sample& b) { return a.z > b.z; });
  double top = samples.front().z;
  // A pattern search in (r, θ) from each of the best nodes: a peak between nodes (a
  // lenslet's vertex) is found to well under the margin.
  for (auto s = samples.begin(); s != best; ++s) {
    double r = s->r, theta = s->theta, z = s->z;
    double dr = span / (kRadii - 1), dt = 2 * std::numbers::pi / kAngles;
    for (int step = 0; step < 4000 && dr > 1e-7 * std::max(outer_radius, 1.0); ++step) {
      bool moved = false;
      for (const auto& [sr, st] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const double rn = std::clamp(r + sr * dr, inner_radius, outer_radius);
        const double tn = theta + st * dt;
        const double zn = sag_at(surface, rn, tn);
        if (zn > z) {
          r = rn, theta = tn, z = zn, moved = true;
          break;
        }
      }
      if (!moved) dr *= 0.5, dt *= 0.5;
    }
    top = std::max(top, z);
  }
  return top;
}

double program_z_ceiling(const Surface& surface, double inner_radius, double outer_radius,
                         const CompensationOptions& o, double stand_off) {
  double waviness = 0;
  for (const auto& [psi, delta] : o.tool.waviness) waviness = std::max(waviness, delta);
  // The programmed point above the nose centre, at most: offset·cos B, with cos B ≤ 1 for
  // a pivot above it, and a tip's −R cos B exact when B is fixed (else bounded by 0).
  const double offset = programmed_point_offset(o);
  const double point = offset > 0                      ? offset
                       : o.b_mode == BMode::kFixed ? offset * std::cos(o.b_fixed)
                                                       : 0.0;
  return highest_sag(surface, inner_radius, outer_radius) + o.tool.nose_radius + waviness +
         stand_off + point + kCeilingMargin;
}

}  // namespace freeturn
