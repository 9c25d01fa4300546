#include "freeturn/path/cutter_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "freeturn/path/section_envelope.hpp"
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
  const auto sample = [&](const RadialLine& line, double rho, double& p, double& t) {
    double z, zx, zy;
    design.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
    p = -std::atan(zx * line.cos + zy * line.sin);  // n ∝ (−∇z, 1)
    t = std::abs(zy * line.cos - zx * line.sin);    // |∇z · e_θ|
  };
  // Over the samples of the line within `apart` of a crease at c: the steepest s_t with the
  // largest change between neighbours on one side of it (what s_t can reach between
  // samples), and the extremes of ψ.
  struct Window {
    double steepest = 0, change = 0, psi_lo = INFINITY, psi_hi = -INFINITY;
  };
  const auto window = [&](double c, double apart) {
    Window w;
    const int i0 = std::max(0, static_cast<int>(std::floor((c - apart - lo) / step)));
    const int i1 = std::min(kSteps, static_cast<int>(std::ceil((c + apart - lo) / step)));
    for (int i = i0; i <= i1; ++i) {
      if (!std::isfinite(psi[i]) || !std::isfinite(across[i])) continue;
      w.steepest = std::max(w.steepest, across[i]);
      w.psi_lo = std::min(w.psi_lo, psi[i]), w.psi_hi = std::max(w.psi_hi, psi[i]);
      const bool same_side = i > i0 && (lo + (i - 1) * step - c) * (lo + i * step - c) > 0;
      if (same_side && std::isfinite(across[i - 1]))
        w.change = std::max(w.change, std::abs(across[i] - across[i - 1]));
    }
    return w;
  };
  // How the nose meets the crease c on `line`, placed as the planner places it
  // (nose_touch) from a contact on either side of it.
  //  - Held (a valley, or a trough narrower than the nose, at c or a crease beside it): its
  //    own touches ρ₁, ρ₂ take the window's place, (s_t(ρ₁) + s_t(ρ₂))·β·|ρ₂ − ρ₁| ≤
  //    2·max s_t·β·|ρ₂ − ρ₁|, β at the nearer touch, s_t the largest at either touch's
  //    radius on this line and on the lines half-way to its neighbours (2π/512 apart).
  //  - Rolling (a ridge): it touches once, at the ridge or beside it, and the first-order
  //    term does not arise; the window's bound stands for the second-order ones, but with
  //    β at the ridge, where the touch is, not at c − R·Δψ, where a second touch would be.
  //  - Neither, or the design undefined there: the window's bound as it is.
  // The window alone took β at c − R·Δψ, and near the axis, where the next lenslets' slopes
  // widen Δψ until that falls below h, it took β = π/2 whatever h was: domes 0.29 mm in
  // radius, 0.22 mm across, with one on the axis, and bowls in a hexagonal array, were
  // refused with reaches of 0.26 and 0.23 mm for h of 10 nm and 2 µm.
  struct CreaseTouches {
    bool defined = true, held = false, rolls = false;
    double held_reach = 0;
  };
  const double half_gap = std::numbers::pi / kLines;
  const auto touches_at = [&](const RadialLine& line, double c) {
    CreaseTouches out;
    for (const double side : {-1.0, 1.0}) {
      const double contact = c + side * 1e-7;
      double z, zx, zy;
      design.sag_gradient(contact * line.cos, contact * line.sin, z, zx, zy);
      const double slope = zx * line.cos + zy * line.sin;
      if (!std::isfinite(z) || !std::isfinite(slope)) return CreaseTouches{false};
      const NoseTouch t = nose_touch(design, line, R, contact, z, slope);
      out.rolls |= t.rolling;
      if (!t.held) continue;  // one touch: nothing to turn out of the plane
      out.held = true;
      const double near = std::min(std::abs(t.rho), std::abs(t.far_rho));
      const double beta = std::asin(std::min(1.0, h / std::max(near, h)));
      double tangential = 0;
      for (const double turn : {-half_gap, 0.0, half_gap}) {
        const RadialLine beside(line.theta + turn);
        for (const double rho : {t.rho, t.far_rho}) {
          double p, s_t;
          sample(beside, rho, p, s_t);
          if (!std::isfinite(s_t)) return CreaseTouches{false};
          tangential = std::max(tangential, s_t);
        }
      }
      out.held_reach =
          std::max(out.held_reach, 2 * tangential * beta * std::abs(t.far_rho - t.rho));
    }
    if (!std::isfinite(out.held_reach)) out.defined = false;
    return out;
  };
  double largest = 0;
  for (int j = 0; j < kLines; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / kLines);
    for (int i = 0; i <= kSteps; ++i) sample(line, lo + i * step, psi[i], across[i]);
    // The line's creases, kCreases at a time (a fine array meets more).
    for (double from = lo;;) {
      const int found = design.section_creases(line, from, outer_radius, creases);
      for (int k = 0; k < std::min(found, kCreases); ++k) {
        const double c = creases[static_cast<std::size_t>(k)];
        // The touches lie R|sin ψ1 − sin ψ2| ≤ R|ψ1 − ψ2| apart with the crease between
        // them, so within `apart` of it when their normals' angles differ by no more than
        // apart/R: from 2R (any two), each window's span of ψ bounds the next, narrower one.
        double apart = 2 * R + step;
        Window w = window(c, apart);
        for (int narrowing = 0; narrowing < 4 && w.psi_hi > w.psi_lo; ++narrowing) {
          const double next = R * (w.psi_hi - w.psi_lo) + step;
          if (!(next < apart)) break;
          apart = next;
          w = window(c, apart);
        }
        if (!(w.psi_hi > w.psi_lo)) continue;
        const CreaseTouches t = touches_at(line, c);
        const auto window_reach = [&](double nearest) {
          const double beta = std::asin(std::min(1.0, h / std::max(nearest, h)));
          return 2 * (w.steepest + w.change) * beta * R * (w.psi_hi - w.psi_lo);
        };
        double reach = t.held ? t.held_reach : 0.0;
        if (!t.defined || !(t.held || t.rolls))
          reach = window_reach(c - apart);
        else if (t.rolls)
          reach = std::max(reach, window_reach(c));
        largest = std::max(largest, reach);
      }
      if (found <= kCreases) break;  // more: the lowest kCreases were listed
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
