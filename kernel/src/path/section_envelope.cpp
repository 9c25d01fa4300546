#include "freeturn/path/section_envelope.hpp"

#include <algorithm>
#include <cmath>

namespace freeturn {
namespace {

// A search starts this far off a crease, so that it evaluates the flank on its own side.
constexpr double kOffCrease = 1e-10;  // mm

struct Section {
  const Surface& design;
  double ct, st;
  Section(const Surface& s, double theta) : design(s), ct(std::cos(theta)), st(std::sin(theta)) {}
  // g(ρ) and dg/dρ; false where the design is undefined.
  bool at(double rho, double& g, double& slope) const {
    double fx, fy;
    design.sag_gradient(rho * ct, rho * st, g, fx, fy);
    slope = fx * ct + fy * st;
    return std::isfinite(g) && std::isfinite(slope);
  }
};

// Newton steps on h(ρ) = g(ρ) − z_c + √(R² − (ρ − x_c)²) within [lo, hi], keeping the
// largest h met in `best`.
void search(const Section& section, double x_c, double z_c, double R, double start, double lo,
            double hi, int steps, NoseOverlap& best) {
  if (!(lo <= hi)) return;
  double r = std::clamp(start, lo, hi);
  for (int it = 0; it < steps; ++it) {
    double g, slope;
    if (!section.at(r, g, slope)) return;
    const double d = r - x_c, s = std::sqrt(std::max(R * R - d * d, 0.0));
    const double h = g - z_c + s;
    if (h > best.height) best = {h, r, slope};
    if (!(s > 0)) return;
    const double next = std::clamp(r + (slope - d / s) * s * s * s / (R * R), lo, hi);
    if (std::abs(next - r) <= 1e-15 * (1 + std::abs(r))) return;
    r = next;
  }
}

// The pieces between creases: the bounds of the piece on `side` (±1) of crease k.
void piece_bounds(const SectionCreases& c, int k, int side, double lo, double hi, double& a,
                  double& b) {
  if (side > 0) {
    a = c.rho[k] + kOffCrease;
    b = k + 1 < c.count ? c.rho[k + 1] - kOffCrease : hi;
  } else {
    a = k > 0 ? c.rho[k - 1] + kOffCrease : lo;
    b = c.rho[k] - kOffCrease;
  }
}

}  // namespace

NoseOverlap nose_overlap(const Surface& design, double theta, double x_c, double z_c, double R,
                         double hint_rho) {
  const Section section(design, theta);
  const double reach = 0.999 * R, lo = x_c - reach, hi = x_c + reach;
  NoseOverlap best;
  SectionCreases creases;
  creases.find(design, theta, lo, hi);
  // The hint's own piece.
  double a = lo, b = hi;
  for (int k = 0; k < creases.count; ++k) {
    if (creases.rho[k] <= hint_rho) a = creases.rho[k] + kOffCrease;
    if (creases.rho[k] > hint_rho) {
      b = creases.rho[k] - kOffCrease;
      break;
    }
  }
  search(section, x_c, z_c, R, hint_rho, a, b, 2, best);
  for (int k = 0; k < creases.count; ++k)
    for (const int side : {-1, 1}) {
      piece_bounds(creases, k, side, lo, hi, a, b);
      search(section, x_c, z_c, R, creases.rho[k] + side * kOffCrease, a, b, 3, best);
    }
  return best;
}

NoseTouch nose_touch(const Surface& design, double theta, double nose_radius, double rho_p,
                     double z_p, double slope_p, double stand_off, double tolerance) {
  const double R = nose_radius + stand_off;  // the envelope's radius
  NoseTouch t;
  t.rho = rho_p;
  t.z = z_p;
  t.slope = slope_p;
  const double length = std::sqrt(1 + slope_p * slope_p);
  t.centre_x = rho_p - R * slope_p / length;
  t.centre_z = z_p + R / length;
  if (!(R > 0) || !design.has_creases()) return t;
  const Section section(design, theta);
  const double reach = 0.999 * R;
  SectionCreases creases;
  // Every crease within 2R: those under the nose may be overhung, and the ones beyond bound
  // the flanks the held nose is solved on (a flank ends at the next crease).
  creases.find(design, theta, std::min(rho_p, t.centre_x) - 2 * R,
               std::max(rho_p, t.centre_x) + 2 * R);
  // The crease whose other flank the nose overhangs most.
  int held_at = -1, far = 0;
  NoseOverlap worst;
  worst.height = tolerance;
  for (int k = 0; k < creases.count; ++k) {
    if (!(std::abs(creases.rho[k] - t.centre_x) < reach) &&
        !(std::abs(creases.rho[k] - rho_p) <= kOffCrease))
      continue;
    const int side = creases.rho[k] > rho_p + kOffCrease ? 1 : -1;
    double a, b;
    piece_bounds(creases, k, side, t.centre_x - reach, t.centre_x + reach, a, b);
    NoseOverlap o;
    search(section, t.centre_x, t.centre_z, R, creases.rho[k] + side * kOffCrease, a, b, 4, o);
    if (o.height > worst.height) {
      worst = o;
      held_at = k;
      far = side;
    }
  }
  if (held_at < 0) return t;

  const double crease = creases.rho[held_at];
  // The other flank, as far as the next crease or 2R.
  double far_lo, far_hi;
  piece_bounds(creases, held_at, far, crease - 2 * R, crease + 2 * R, far_lo, far_hi);
  // The contact's own flank, likewise.
  double near_lo, near_hi;
  piece_bounds(creases, held_at, -far, crease - 2 * R, crease + 2 * R, near_lo, near_hi);

  double foot = worst.rho;  // warm start of the foot point on the other flank
  double centre_x = 0, centre_z = 0, g_a = 0, slope_a = 0;
  // F(a) = R − distance from the offset of the own flank at a to the other flank: > 0 where
  // the nose there overhangs it, 0 at the intersection of the two offsets.
  const auto F = [&](double a) {
    if (!section.at(a, g_a, slope_a)) return -R;
    const double l = std::sqrt(1 + slope_a * slope_a);
    centre_x = a - R * slope_a / l;
    centre_z = g_a + R / l;
    // The distance is that of the last foot evaluated, taken once after the iterations
    // (std::hypot costs as much as the rest of an iteration).
    double g, s, dx = 1e300, dz = 0;
    for (int it = 0; it < 12; ++it) {
      if (!section.at(foot, g, s)) return -R;
      dx = foot - centre_x;
      dz = g - centre_z;
      const double next = std::clamp(foot - (dx + s * dz) / (1 + s * s), far_lo, far_hi);
      if (std::abs(next - foot) <= 1e-15 * (1 + std::abs(foot))) break;
      foot = next;
    }
    return R - std::hypot(dx, dz);
  };
  const double own = std::clamp(rho_p, near_lo, near_hi);
  double a_in = own, f_in = F(a_in);
  if (!(f_in > 0)) return t;  // the overhang is not this flank's to resolve
  // Step away from the crease along the own flank until the offset clears the other one.
  double a_out = a_in, f_out = f_in;
  for (double step = std::max(std::abs(crease - own), 1e-4 * R);; step *= 2) {
    a_out = std::clamp(crease - far * step, near_lo, near_hi);
    f_out = F(a_out);
    if (f_out < 0) break;
    if (step > 2 * R || a_out == near_lo || a_out == near_hi) return t;
  }
  // Illinois regula falsi on [a_out, a_in].
  int kept = 0;
  double a = a_in;
  for (int it = 0; it < 100; ++it) {
    a = (a_out * f_in - a_in * f_out) / (f_in - f_out);
    const double f = F(a);
    if (std::abs(f) <= 1e-14 || std::abs(a_in - a_out) <= 1e-14) break;
    if (f > 0) {
      a_in = a;
      f_in = f;
      if (kept == 1) f_out *= 0.5;
      kept = 1;
    } else {
      a_out = a;
      f_out = f;
      if (kept == -1) f_in *= 0.5;
      kept = -1;
    }
  }
  F(a);  // leaves the centre and the flank's values at a
  t.rho = a;
  t.z = g_a;
  t.slope = slope_a;
  t.centre_x = centre_x;
  t.centre_z = centre_z;
  t.held = true;
  t.crease_rho = crease;
  t.far_rho = foot;
  double g_crease, s_crease;
  section.at(crease, g_crease, s_crease);
  const double d = crease - centre_x;
  t.uncut = centre_z - std::sqrt(std::max(nose_radius * nose_radius - d * d, 0.0)) - g_crease;
  return t;
}

}  // namespace freeturn
