#include "freeturn/path/cutter_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "freeturn/surface/section_curvature.hpp"

namespace freeturn {

double smooth_wavy_edge_reach(const ToolMotion& tool, const Surface& design, double inner_radius,
                              double outer_radius) {
  if (!(tool.waviness_span > 0) || !(tool.nose_radius > 0)) return 0.0;
  const double R = tool.nose_radius, L = tool.waviness_slope;
  // A section convex everywhere (κ ≤ 0) leaves the nose the most room at κ = 0 that counts
  // here (more is not needed: L²/2R is a fraction of a nanometre for any real edge).
  const double kappa = std::max(0.0, largest_section_curvature(design, inner_radius, outer_radius));
  const double room = R * (1 - kappa * R);  // the nose's clearance grows as room·Δφ²/2
  if (!(room > 0)) return tool.waviness_span;
  return std::min(tool.waviness_span, L * L / (2 * room));
}

double centre_height_reach(const ToolMotion& tool, const Surface& design, double inner_radius,
                           double outer_radius) {
  const double h = std::abs(tool.centre_height), R = tool.nose_radius;
  if (!(h > 0) || !(R > 0) || !design.has_creases()) return 0.0;
  // Sampled on kLines radial lines at kSteps + 1 radii each (ψ and s_t on both sides of
  // every crease a line meets), as the curvature's grid is: a sample, not a bound.
  constexpr int kLines = 512, kSteps = 512, kCreases = 256;
  const double lo = std::max(inner_radius, h), step = (outer_radius - lo) / kSteps;
  if (!(step > 0)) return 0.0;
  std::vector<double> psi(kSteps + 1), across(kSteps + 1);
  std::array<double, kCreases> creases;
  double psi_min = INFINITY, psi_max = -INFINITY;
  const auto sample = [&](const RadialLine& line, double rho, double& p, double& t) {
    double z, zx, zy;
    design.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
    p = -std::atan(zx * line.cos + zy * line.sin);  // n ∝ (−∇z, 1)
    t = std::abs(zy * line.cos - zx * line.sin);    // |∇z · e_θ|
  };
  // The span of the section normals' angles first: it bounds how far apart two touches lie.
  for (int j = 0; j < kLines; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / kLines);
    for (int i = 0; i <= kSteps; ++i) {
      sample(line, lo + i * step, psi[i], across[i]);
      if (std::isfinite(psi[i]))
        psi_min = std::min(psi_min, psi[i]), psi_max = std::max(psi_max, psi[i]);
    }
  }
  if (!(psi_max > psi_min)) return 0.0;
  const double apart = R * (psi_max - psi_min) + step;
  double largest = 0;
  for (int j = 0; j < kLines; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / kLines);
    for (int i = 0; i <= kSteps; ++i) sample(line, lo + i * step, psi[i], across[i]);
    // The line's creases, kCreases at a time (a fine array meets more).
    for (double from = lo;;) {
      const int found = design.section_creases(line, from, outer_radius, creases);
      for (int k = 0; k < found; ++k) {
        const double c = creases[static_cast<std::size_t>(k)];
        // Both touches lie within `apart` of the crease; the steepest slope and the widest
        // angle between normals there, with the largest change between neighbouring samples
        // on either side (what the slope can reach between them).
        const int i0 = std::max(0, static_cast<int>(std::floor((c - apart - lo) / step)));
        const int i1 = std::min(kSteps, static_cast<int>(std::ceil((c + apart - lo) / step)));
        double steepest = 0, change = 0, p_lo = INFINITY, p_hi = -INFINITY;
        for (int i = i0; i <= i1; ++i) {
          if (!std::isfinite(psi[i]) || !std::isfinite(across[i])) continue;
          steepest = std::max(steepest, across[i]);
          p_lo = std::min(p_lo, psi[i]), p_hi = std::max(p_hi, psi[i]);
          const bool same_side = i > i0 && (lo + (i - 1) * step - c) * (lo + i * step - c) > 0;
          if (same_side && std::isfinite(across[i - 1]))
            change = std::max(change, std::abs(across[i] - across[i - 1]));
        }
        if (!(p_hi > p_lo)) continue;
        const double beta = std::asin(std::min(1.0, h / std::max(c - apart, h)));
        largest = std::max(largest, 2 * (steepest + change) * beta * R * (p_hi - p_lo));
      }
      if (found < kCreases) break;
      from = std::nextafter(creases[kCreases - 1], INFINITY);
    }
  }
  return largest;
}

void measure_edge_reach(ToolMotion& tool, const Surface& design, double inner_radius,
                        double outer_radius) {
  tool.smooth_waviness_reach = smooth_wavy_edge_reach(tool, design, inner_radius, outer_radius);
  tool.centre_height_reach = centre_height_reach(tool, design, inner_radius, outer_radius);
}

}  // namespace freeturn
