#include "freeturn/path/section_envelope.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>
#include <numbers>
#include <span>

#include "freeturn/surface/section_curvature.hpp"

namespace freeturn {
namespace {

// A search starts this far off a crease, so that it evaluates the flank on its own side.
constexpr double kOffCrease = 1e-10;  // mm

// How far below a piece's top nose_overlap may leave it, where the piece's concavity shows
// it can rise no more above the largest height found (a tenth of a picometre).
constexpr double kUnsought = 1e-13;  // mm
// How close to a piece's peak a search that has passed its floor goes on to (search).
constexpr double kSettled = 1e-9;  // mm

struct Section {
  const Surface& design;
  double ct, st;
  Section(const Surface& s, const RadialLine& line) : design(s), ct(line.cos), st(line.sin) {}
  // g(ρ) and dg/dρ; false where the design is undefined.
  bool at(double rho, double& g, double& slope) const {
    double fx, fy;
    design.sag_gradient(rho * ct, rho * st, g, fx, fy);
    slope = fx * ct + fy * st;
    return std::isfinite(g) && std::isfinite(slope);
  }
  // And the curvature term d²g/dρ².
  bool at(double rho, double& g, double& slope, double& bend) const {
    const HeightDerivatives h = design.height_derivatives(rho * ct, rho * st);
    g = h.z;
    slope = h.zx * ct + h.zy * st;
    bend = (h.zxx * ct + 2 * h.zxy * st) * ct + h.zyy * st * st;
    return std::isfinite(g) && std::isfinite(slope) && std::isfinite(bend);
  }
};

// The point where the offsets (radius R) of two flanks meet: own-flank abscissa a in
// [a_lo, a_hi], far-flank abscissa b in [b_lo, b_hi], from (a, b) as given. The offset of
// the section at x is O(x) = (x, g) + R(−g', 1)/L with L = √(1 + g'²), and
// dO/dx = (1 − R g''/L³)(1, g'), so Newton's 2×2 system O(a) = O(b) has the Jacobian
// [k_a (1, g'_a), −k_b (1, g'_b)], of determinant k_a k_b (g'_a − g'_b): regular wherever
// the flanks meet at an angle and neither offset has a cusp (k > 0). Converges in a few
// steps from the overhang found (the flanks are nearly straight over a nose); false if an
// iterate leaves a flank or it does not converge, and the caller solves it another way.
// On success: the own flank's value and slope at a, and the centre O(a).
bool offsets_meet(const Section& section, double R, double a_lo, double a_hi, double b_lo,
                  double b_hi, double& a, double& b, double& g_a, double& slope_a,
                  double& centre_x, double& centre_z) {
  double last_step = 1e300;
  for (int it = 0; it < 16; ++it) {
    double g_b, slope_b, bend_a, bend_b;
    if (!(a >= a_lo && a <= a_hi && b >= b_lo && b <= b_hi)) return false;
    if (!section.at(a, g_a, slope_a, bend_a) || !section.at(b, g_b, slope_b, bend_b)) return false;
    const double l_a = std::sqrt(1 + slope_a * slope_a), l_b = std::sqrt(1 + slope_b * slope_b);
    centre_x = a - R * slope_a / l_a;
    centre_z = g_a + R / l_a;
    const double rx = centre_x - (b - R * slope_b / l_b), rz = centre_z - (g_b + R / l_b);
    // Met to rounding, or the last step was at rounding's scale (quadratic convergence:
    // this residual is rounding too).
    if ((std::abs(rx) <= 4e-15 * (1 + std::abs(centre_x)) &&
         std::abs(rz) <= 4e-15 * (1 + std::abs(centre_z))) ||
        last_step <= 1e-14 * (1 + std::abs(a)))
      return true;
    const double k_a = 1 - R * bend_a / (l_a * l_a * l_a);
    const double k_b = 1 - R * bend_b / (l_b * l_b * l_b);
    const double det = k_a * k_b * (slope_a - slope_b);
    if (!(k_a > 0 && k_b > 0) || !(std::abs(det) > 1e-12)) return false;
    // [k_a, −k_b; k_a g'_a, −k_b g'_b] (da, db) = −(rx, rz), by Cramer's rule.
    const double da = (rx * k_b * slope_b - k_b * rz) / det;
    const double db = (k_a * slope_a * rx - k_a * rz) / det;
    a += da;
    b += db;
    last_step = std::max(std::abs(da), std::abs(db));
  }
  return false;
}

// h(ρ) = g(ρ) − z_c + √(R² − (ρ − x_c)²) and h'(ρ) at r from the section's value g and slope
// there, the largest h kept in `best`. s = √(R² − (r − x_c)²); false at the end of the arc
// (s = 0), where no step can be taken.
bool arc_height(double r, double g, double slope, double x_c, double z_c, double R,
                NoseOverlap& best, double& h, double& s, double& h_slope) {
  const double d = r - x_c;
  s = std::sqrt(std::max(R * R - d * d, 0.0));
  h = g - z_c + s;
  if (h > best.height) best = {h, r, slope};
  if (!(s > 0)) return false;
  h_slope = slope - d / s;
  return true;
}

// The last two points a search evaluated and h' there: the secant's h'' (settle_by_secant).
struct SecantPoints {
  double last_r = 0, last_h_slope = 0, previous_r = 0, previous_h_slope = 0;
  int evaluated = 0;
  void add(double r, double h_slope) {
    previous_r = last_r, previous_h_slope = last_h_slope;
    last_r = r, last_h_slope = h_slope, ++evaluated;
  }
  // (h'₂ − h'₁)/(ρ₂ − ρ₁); NaN before two distinct points.
  double curvature() const {
    return evaluated >= 2 && last_r != previous_r
               ? (last_h_slope - previous_h_slope) / (last_r - previous_r)
               : std::numeric_limits<double>::quiet_NaN();
  }
};

// The steps of `search` take h'' as the nose's alone (−R²/s³). Where the section bends
// toward the tool nearly as much as the nose (g'' close to 1/R: a concave design under a
// nose that just fits it), the true h'' is a small fraction of that, each step covers only
// that fraction of the way to the peak, and two of them left a sinusoidal grid's overlap
// 4 to 61 nm short, so that a chord dipped that far below the design unseen. From the
// last two points evaluated (ρ₁ before ρ₂, h' there) the secant gives h'', and the peak
// lies about h'(ρ₂)²/(2|h''|) higher: while that is more than kSettled, go on from `next`
// (the step already taken from ρ₂) by the secant's Newton steps, which converge
// superlinearly on a smooth piece. Where the secant shows no concavity the section bends
// more than the nose (the local gouge check's finding, at the contacts): h has no peak
// near the hint, and the search stops as before. The peak at an end of [lo, hi] (h'
// pointing out of it) is settled there.
void settle_by_secant(const Section& section, double x_c, double z_c, double R, double lo,
                      double hi, double next, SecantPoints points, NoseOverlap& best) {
  const auto gain = [&] {
    const double r = points.last_r, h_slope = points.last_h_slope;
    if ((r <= lo && h_slope <= 0) || (r >= hi && h_slope >= 0)) return 0.0;
    const double curvature = points.curvature();
    return curvature < 0 ? h_slope * h_slope / (-2 * curvature) : 0.0;
  };
  for (int it = 0; it < 32 && gain() > kSettled; ++it) {
    if (std::abs(next - points.last_r) <= 1e-15 * (1 + std::abs(points.last_r))) return;
    double g, slope, h, s, h_slope;
    if (!section.at(next, g, slope)) return;
    if (!arc_height(next, g, slope, x_c, z_c, R, best, h, s, h_slope)) return;
    points.add(next, h_slope);
    const double curvature = points.curvature();
    if (!(curvature < 0)) return;
    next = std::clamp(next - h_slope / curvature, lo, hi);
  }
}

// Newton steps on h(ρ) = g(ρ) − z_c + √(R² − (ρ − x_c)²) within [lo, hi], keeping the
// largest h met in `best`.
//
// `ceiling` (with m > 0): lowered to the least bound of the piece's maximum that the values
// met give. h is m-strongly concave on it, so max h ≤ h(r) + h'(r)²/(2m) from any r, with
// h'(r) taken as 0 at an end of [lo, hi] where h falls into the piece.
//
// A search from a crease (start at the end of its piece on the crease's side, the piece
// reaching `side` (±1) from there) stops after its first value where the piece cannot
// rise to `floor`: h is m-strongly concave on it (`m`, section_concavity()), so nowhere on it
// does h exceed h₀ + max(0, side·h'₀)²/(2m). Such a search could only have kept values
// below `floor`, which the caller compares with a larger one; leaving it out changes no
// answer (a margin of 1e-12 mm covers the rounding of both).
//
// `up` (with m ≤ 0): a bound of h'' on the piece, h'' = g'' − R²/s³ ≤ max_section_bend − 1/R
// (piece_bend). A piece that bends more than the nose somewhere has no concavity
// bound, but h still lies under the parabola h₀ + h'₀(ρ − ρ₀) + up(ρ − ρ₀)²/2 from any
// value, whose largest value on [lo, hi] is at an end: a search from a crease whose
// parabola stays below `floor` stops after its first value there too.
//
// Returns whether the search stopped on such a bound: the whole piece lies below `floor`.
bool search(const Section& section, double x_c, double z_c, double R, double start, double lo,
            double hi, int steps, NoseOverlap& best, int side = 0, double m = 0,
            double floor = -1e300, double* ceiling = nullptr,
            double up = std::numeric_limits<double>::infinity()) {
  if (!(lo <= hi)) return false;
  double r = std::clamp(start, lo, hi);
  // The least bound of the piece's maximum the values met give (m > 0, as `ceiling`).
  double bound = std::numeric_limits<double>::infinity();
  SecantPoints points;  // for settle_by_secant
  for (int it = 0; it < steps; ++it) {
    double g, slope, h, s, h_slope;
    if (!section.at(r, g, slope)) return false;
    if (!arc_height(r, g, slope, x_c, z_c, R, best, h, s, h_slope)) return false;
    points.add(r, h_slope);
    if (m > 0) {
      const double rise = (r == lo && h_slope < 0) || (r == hi && h_slope > 0) ? 0.0 : h_slope;
      bound = std::min(bound, h + rise * rise / (2 * m));
      if (ceiling) *ceiling = std::min(*ceiling, bound);
    }
    if (it == 0 && side != 0 && r == start) {
      if (m > 0) {
        const double rise = std::max(0.0, side * h_slope);  // into the piece
        if (h + rise * rise / (2 * m) + 1e-12 < floor) return true;
      } else if (up >= 0 && up < std::numeric_limits<double>::infinity()) {
        const auto parabola = [&](double x) {
          return h + (x - r) * (h_slope + 0.5 * up * (x - r));
        };
        if (std::max(parabola(lo), parabola(hi)) + 1e-12 < floor) return true;
      }
    }
    const double next = std::clamp(r + h_slope * s * s * s / (R * R), lo, hi);
    if (std::abs(next - r) <= 1e-15 * (1 + std::abs(r))) return false;
    r = next;
  }
  // The steps above take h'' as the nose's alone (−R²/s³). Where the piece is strongly
  // convex too (a steep lenslet), they overshoot and can end far from a peak that the
  // bound still says may pass `floor`, or what was found: a nose held nowhere over a
  // lenslet 0.25 µm inside it, and a held nose's touch on a lenslet read as 0.24 µm
  // short of it. Such a search goes on by Newton's method with h'' = g'' − R²/s³ until
  // the bound settles it: below `floor`, or within kSettled of the largest value found.
  const auto settled = [&] {
    return best.height >= floor ? bound <= best.height + kSettled : bound + 1e-12 < floor;
  };
  if (!(floor > -1e300)) {
    // A search from the hint that keeps its piece's ceiling under a concavity bound (the
    // hint's on a creased section) needs no more: nose_overlap searches that piece again
    // from each crease beside it while the ceiling leaves room above the largest height
    // found, and those searches settle it by the bound. On the compound eye (2 mm of the
    // 2M job, 560 k points) the secant here took 0.85 M more evaluations; 59 k remain in
    // the searches that go on.
    if (!(ceiling && m > 0)) settle_by_secant(section, x_c, z_c, R, lo, hi, r, points, best);
    return false;
  }
  if (!(m > 0)) {
    // No concavity bound (a section whose troughs bend more tightly than the nose, or a
    // design that gives none): its Newton steps alone had ended a held nose's search for
    // its far touch 140 nm short, on the ring of docs/tool.md's tight troughs.
    settle_by_secant(section, x_c, z_c, R, lo, hi, r, points, best);
    return false;
  }
  if (settled()) return false;
  for (int it = 0; it < 40; ++it) {
    double g, slope, bend, h, s, h_slope;
    if (!section.at(r, g, slope, bend)) return false;
    if (!arc_height(r, g, slope, x_c, z_c, R, best, h, s, h_slope)) return false;
    const double rise = (r == lo && h_slope < 0) || (r == hi && h_slope > 0) ? 0.0 : h_slope;
    bound = std::min(bound, h + rise * rise / (2 * m));
    if (ceiling) *ceiling = std::min(*ceiling, bound);
    if (settled()) return false;
    const double curvature = std::min(bend - R * R / (s * s * s), -m);  // h'' ≤ −m on the piece
    const double next = std::clamp(r - h_slope / curvature, lo, hi);
    if (std::abs(next - r) <= 1e-15 * (1 + std::abs(r))) return false;
    r = next;
  }
  return false;
}

// How the nose's height over a section piece within `radius` of the axis can curve, from one
// bound of the design's bend: h'' = g'' − R²/s³ ≤ max_section_bend − 1/R = up, since s ≤ R. Where
// up is negative, h is m-strongly concave with m = −up (section_concavity); otherwise m is 0 and up
// (+∞ where the design gives no bound) is search's parabola.
struct PieceBend {
  double m, up;
};
PieceBend piece_bend(const Surface& design, double R, double radius) {
  const double up = design.max_section_bend(radius) - 1 / R;
  return {up < 0 ? -up : 0.0, up};
}

// The pieces between creases: the bounds of the piece on `side` (±1) of crease k, within
// [lo, hi] (the nose's reach). A crease found beyond the reach (the creases are listed 2R
// about the contact) bounds no piece under the nose: a search's Newton step clamped to it
// left the arc's footprint and ended the search on its first value. On a steep dome's
// wall (a 0.11 mm lens under a 0.2 mm nose) the first step from the near rim overshot so,
// and a free nose was placed 3 nm from a wall its stand-off's envelope overhung by 122 nm.
void piece_bounds(const SectionCreases& c, int k, int side, double lo, double hi, double& a,
                  double& b) {
  if (side > 0) {
    a = c.rho[k] + kOffCrease;
    b = k + 1 < c.count ? std::min(hi, c.rho[k + 1] - kOffCrease) : hi;
  } else {
    a = k > 0 ? std::max(lo, c.rho[k - 1] + kOffCrease) : lo;
    b = c.rho[k] - kOffCrease;
  }
}

// One crease's part of the envelope below: a slope `rise` gained past the distance `from`.
// Without initialisers: the arrays of them below are filled as they are used, and zeroing
// 16 or 32 of them at every certificate was 0.6 % of a chord job's instructions.
struct EnvelopeTerm {
  double from;
  double rise;
};

// Whether E(t) = −m t²/2 + Σ_k rise_k (t − from_k)₊ < 0 for lo < t ≤ hi (lo ≥ 0); the
// terms sorted by `from`, each from > 0 (below the first, E < 0). Past the k-th term
// E(t) = −m t²/2 + rise·t − offset, rise = Σ rise_k and offset = Σ rise_k from_k over the
// terms passed: its largest value on [from_k, from_{k+1}] is at rise/m, clamped there.
bool envelope_below_zero(const EnvelopeTerm* terms, int count, double m, double lo, double hi) {
  double rise = 0, offset = 0;
  for (int k = 0; k < count; ++k) {
    const double d = terms[k].from;
    if (d >= hi) break;
    rise += terms[k].rise;
    offset += terms[k].rise * d;
    const double next = k + 1 < count ? std::min(hi, terms[k + 1].from) : hi;
    if (next < lo) continue;
    const double t = std::clamp(rise / m, std::max(d, lo), std::max(d, next));
    if (!(-0.5 * m * t * t + rise * t - offset < 0)) return false;
  }
  return true;
}

// The envelope again where the creases say how their rims lie (NearbyCrease's normal), for
// the sections of touches within `margin` of (x, y): the radial lines through them, within
// δ = asin(margin/|(x, y)|) of this one's direction u. The terms `plain` (the creases within
// reach, d_k = distance − margin > 0, in near's order) already failed.
//
// A section crosses a rim at q, s along it from the touch T', at the angle ψ between the
// line and the rim's normal ν(q): the slope rises there by J|cos ψ| at most, so the section
// gains J c (t − s)₊, c = |cos ψ|, and c·s = p is T''s distance from the rim's tangent at q.
// - From inside the convex footprint the line leaves it once, and p ≥ T''s distance from the
//   rim ≥ d (the tangent supports the footprint): J c (t − s)₊ ≤ J c (t − d/c)₊.
// - From outside it enters at q₁ and may leave at q₂. The footprint holds the disc of
//   radius 1/κ that touches its rim at q₁ from inside (Blaschke's rolling theorem; κ the
//   rim's largest curvature), and T' lies at least d from that disc: p₁ ≥ d − κ s₁²/2, so
//   J c₁ (t − s₁)₊ ≤ J c (t − d/c)₊ + J κ t²/2 (the last term taken into m). The exit,
//   farther than d, adds J c (t − d)₊.
// Only t ≤ t_max = 2ΣJ_k n_k/m can matter: past it the plain envelope is below 0 whatever the
// angles. On (lo, hi] within it only rim points within L = hi + margin of (x, y) count;
// seen from the footprint's centre e they lie within asin(L/|T − e|) of T's direction, and
// their normals within the crease's normal_slack more. With the line's own δ, c ≤ cos(ψ₀ −
// all three), ψ₀ the angle between u and T's direction from e (1 where that is not past
// them). The nearer the stretch, the tighter the angles: (0, t_max] is taken in halves from
// the far end, down to the nearest crease (E < 0 before it).
bool directed_envelope_below_zero(const NearbyCrease* near, const EnvelopeTerm* plain, int within,
                                  double m, double reach, double x, double y, double margin) {
  const double rho = std::sqrt(x * x + y * y);  // mm: std::hypot's care for overflow is not needed
  if (!(rho > margin) || within == 0) return false;
  const double line_spread = std::asin(margin / rho), ux = x / rho, uy = y / rho;
  double total = 0;
  for (int k = 0; k < within; ++k) total += plain[k].rise;
  const double t_max = std::min(reach, 2 * total / m);
  const double nearest = plain[0].from;
  // Per crease, what the tiers share: the angle X = ψ₀ − (normal_slack + δ) left once the
  // parts of the spread that do not depend on L are taken off, by its sine and cosine. A
  // tier then takes off β = asin(L/|T − e|) too, c = cos(X − β) where X > β, without a sine
  // or cosine of its own: X ≤ ψ₀ ≤ π/2 and β ∈ [0, π/2], so X > β ⟺ sin X > L/|T − e|, and
  // cos(X − β) = cos X cos β + sin X sin β. (Per tier and crease these were an arcsine and a
  // cosine: 13 million calls on the chord job cut to 2 mm, 560 k cutter points.)
  std::array<double, 16> sin_x, cos_x;
  for (int k = 0; k < within; ++k) {
    const NearbyCrease& crease = near[k];
    const double psi =
        std::acos(std::min(1.0, std::abs(ux * crease.normal_x + uy * crease.normal_y)));
    const double x_angle = psi - (crease.normal_slack + line_spread);
    // X ≤ 0: no tier's angle passes its spread (c = 1 throughout).
    sin_x[static_cast<std::size_t>(k)] = x_angle > 0 ? std::sin(x_angle) : 0.0;
    cos_x[static_cast<std::size_t>(k)] = x_angle > 0 ? std::cos(x_angle) : 1.0;
  }
  for (double hi = t_max; hi > nearest;) {
    const double lo = std::max(nearest, 0.5 * hi);
    const double L = hi + margin;
    std::array<EnvelopeTerm, 32> terms;
    int n = 0;
    double m_directed = m;
    for (int k = 0; k < within; ++k) {
      const NearbyCrease& crease = near[k];
      const double d = plain[k].from;
      double c = 1;
      const bool known = crease.centre_distance > 0 && crease.normal_slack >= 0 &&
                         (crease.crossings == 1 || (crease.crossings == 2 && crease.curvature > 0 &&
                                                    std::isfinite(crease.curvature)));
      if (known && L < crease.centre_distance) {  // else β = π/2 ≥ X: c = 1
        const double sin_beta = L / crease.centre_distance;
        const double sx = sin_x[static_cast<std::size_t>(k)];
        if (sx > sin_beta)
          c = cos_x[static_cast<std::size_t>(k)] * std::sqrt(1 - sin_beta * sin_beta) +
              sx * sin_beta;
      }
      if (!(c < 1)) {
        terms[static_cast<std::size_t>(n++)] = plain[k];
        continue;
      }
      const double jump = crease.slope_jump * c;
      terms[static_cast<std::size_t>(n++)] = {d / c, jump};
      if (crease.crossings == 2) {
        terms[static_cast<std::size_t>(n++)] = {d, jump};
        if (d < hi) m_directed -= crease.slope_jump * crease.curvature;
      }
    }
    if (!(m_directed > 0)) return false;
    std::sort(terms.begin(), terms.begin() + n,
              [](const EnvelopeTerm& a, const EnvelopeTerm& b) { return a.from < b.from; });
    // The farthest stretch's angles are the widest and its m the least, so its envelope
    // lies above every nearer stretch's: below zero over all of (nearest, t_max], it
    // answers for them all (on the chord cut, 41 % of the calls that end true).
    if (hi == t_max && envelope_below_zero(terms.data(), n, m_directed, nearest, hi)) return true;
    if (!envelope_below_zero(terms.data(), n, m_directed, lo, hi)) return false;
    hi = lo;
  }
  return true;
}

}  // namespace

double section_concavity(const Surface& design, double R, double radius) {
  return piece_bend(design, R, radius).m;
}

NoseOverlap nose_overlap(const Surface& design, const RadialLine& line, double x_c, double z_c, double R,
                         double hint_rho) {
  const Section section(design, line);
  const double reach = 0.999 * R, lo = x_c - reach, hi = x_c + reach;
  NoseOverlap best;
  SectionCreases creases;
  // More creases under the nose than the list holds: the nose is taken to be in the
  // design, so that no step is measured clear from a list that leaves some out.
  if (!creases.find(design, line, lo, hi)) {
    best.height = std::numeric_limits<double>::infinity();
    best.rho = x_c;
    return best;
  }
  // The hint's own piece, the `hint_piece`-th (piece p lies between creases p − 1 and p).
  double a = lo, b = hi;
  int hint_piece = 0;
  for (int k = 0; k < creases.count; ++k) {
    if (creases.rho[k] <= hint_rho) {
      a = creases.rho[k] + kOffCrease;
      hint_piece = k + 1;
    }
    if (creases.rho[k] > hint_rho) {
      b = creases.rho[k] - kOffCrease;
      break;
    }
  }
  if (creases.count == 0) {
    search(section, x_c, z_c, R, hint_rho, a, b, 2, best);
    return best;
  }
  const double radius = std::max(std::abs(lo), std::abs(hi));
  const PieceBend bend = piece_bend(design, R, radius);
  const double m = bend.m, up = bend.up;
  // Each piece's ceiling (search): a piece searched before is searched again from a crease
  // only if it may still rise more than kUnsought above the largest height found. Most
  // often the hint's search has found its own piece's top to well under that, and the
  // search from the crease beside it, three steps more, used to find it again.
  std::array<double, SectionCreases::kCapacity + 1> ceiling;
  std::fill(ceiling.begin(), ceiling.begin() + creases.count + 1,
            std::numeric_limits<double>::infinity());
  search(section, x_c, z_c, R, hint_rho, a, b, 2, best, 0, m, -1e300,
         &ceiling[static_cast<std::size_t>(hint_piece)]);
  for (int k = 0; k < creases.count; ++k)
    for (const int side : {-1, 1}) {
      double& piece_ceiling = ceiling[static_cast<std::size_t>(side < 0 ? k : k + 1)];
      if (piece_ceiling <= best.height + kUnsought) continue;
      piece_bounds(creases, k, side, lo, hi, a, b);
      search(section, x_c, z_c, R, creases.rho[k] + side * kOffCrease, a, b, 3, best, side, m,
             best.height, &piece_ceiling, up);
    }
  // Highest at a crease (a ridge the nose passes over): the section has two normals there,
  // and the gap along the flatter flank's is the larger. The material left beside a rim on
  // the plane is the nose's height over the plane, not its distance from the rim along the
  // steeper flank's normal, which read a chord of 218 nm as 196 (a bowl tighter than the
  // nose, its rim crossed at 26°).
  for (int k = 0; k < creases.count; ++k) {
    if (!(std::abs(creases.rho[k] - best.rho) <= 2 * kOffCrease)) continue;
    double g, below, above;
    if (section.at(creases.rho[k] - kOffCrease, g, below) &&
        section.at(creases.rho[k] + kOffCrease, g, above))
      best.slope = std::abs(below) < std::abs(above) ? below : above;
    break;
  }
  return best;
}

NoseOverlap nose_overlap_near(const Surface& design, const RadialLine& line, double x_c, double z_c,
                              double R, double hint_rho) {
  const double reach = 0.999 * R;
  NoseOverlap best;
  search(Section(design, line), x_c, z_c, R, hint_rho, x_c - reach, x_c + reach, 2, best);
  return best;
}

bool crease_lists_whole_under_nose(const Surface& design, double R, double inner, double outer,
                                   double& r, double& theta) {
  if (!(R > 0) || !design.has_creases() || !(outer >= inner)) return true;
  constexpr int kLines = 32, kMostRadii = 512;
  const int radii =
      std::clamp(static_cast<int>(std::ceil((outer - inner) / (0.5 * R))), 1, kMostRadii);
  const double reach = 0.999 * R;  // nose_overlap's
  SectionCreases creases;
  for (int j = 0; j < kLines; ++j) {
    const RadialLine line(2 * std::numbers::pi * j / kLines);
    for (int i = 0; i <= radii; ++i) {
      const double at = inner + (outer - inner) * i / radii;
      if (creases.find(design, line, at - reach, at + reach)) continue;
      r = at;
      theta = line.theta;
      return false;
    }
  }
  return true;
}

bool touch_clear_of_creases(const Surface& design, double x, double y, double R, double margin) {
  const double reach = 2 * R;  // the arc's footprint, from any touch under it
  // Room for the creases, not initialised: creases_near writes each crease it reports
  // whole, and only those are read. (NearbyCrease's members default to 0; constructing 16
  // of them at every certificate was 1.3 % of a chord job's instructions.)
  alignas(NearbyCrease) unsigned char room[16 * sizeof(NearbyCrease)];
  const std::span<NearbyCrease> near(std::launder(reinterpret_cast<NearbyCrease*>(room)), 16);
  const int count = design.creases_near(x, y, reach + margin, near);
  if (count < 0) return false;
  if (count == 0) return true;
  const double m = section_concavity(design, R, std::sqrt(x * x + y * y) + reach);
  if (!(m > 0)) return false;
  std::sort(near.begin(), near.begin() + count,
            [](const NearbyCrease& a, const NearbyCrease& b) { return a.distance < b.distance; });
  // The creases within reach: each d_k = distance − margin, crossed n_k times with a jump
  // of at most J_k along any direction.
  std::array<EnvelopeTerm, 16> plain;
  int within = 0;
  for (int k = 0; k < count; ++k) {
    const NearbyCrease& crease = near[static_cast<std::size_t>(k)];
    const double d = crease.distance - margin;
    if (!(d > 0)) return false;  // the touch may reach the crease
    if (d >= reach) break;
    const double jump = crease.crossings * crease.slope_jump;
    if (!(jump >= 0) || !std::isfinite(jump)) return false;
    plain[static_cast<std::size_t>(within++)] = {d, jump};
  }
  if (envelope_below_zero(plain.data(), within, m, 0, reach)) return true;
  return directed_envelope_below_zero(near.data(), plain.data(), within, m, reach, x, y, margin);
}

namespace {

// The nose for the contact (rho_p, t) held at crease `held_at`, overhanging its flank on
// `far` (±1) at overhang_rho: its centre where the own flank's offset meets the far
// flank's (nose_touch, below). t itself where that is not resolved.
// The material a nose of radius nose_radius about (centre_x, centre_z) leaves above the
// section at a crease under it (mm, vertical): the depth of a held nose's residual there.
// 0 where the design is undefined.
double left_at_crease(const Section& section, double crease, double centre_x, double centre_z,
                      double nose_radius) {
  double g, slope;
  if (!section.at(crease, g, slope)) return 0.0;
  const double d = crease - centre_x;
  return centre_z - std::sqrt(std::max(nose_radius * nose_radius - d * d, 0.0)) - g;
}

NoseTouch hold_at_crease(const Section& section, const SectionCreases& creases, NoseTouch t,
                         double rho_p, double R, double nose_radius, double m, double tolerance,
                         int held_at, int far, double overhang_rho) {
  const double crease = creases.rho[held_at];
  // The other flank, as far as the next crease or 2R.
  double far_lo, far_hi;
  piece_bounds(creases, held_at, far, crease - 2 * R, crease + 2 * R, far_lo, far_hi);
  // The contact's own flank, likewise.
  double near_lo, near_hi;
  piece_bounds(creases, held_at, -far, crease - 2 * R, crease + 2 * R, near_lo, near_hi);

  double foot = overhang_rho;  // warm start of the foot point on the other flank
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
    bool settled = false;
    for (int it = 0; it < 12; ++it) {
      if (!section.at(foot, g, s)) return -R;
      dx = foot - centre_x;
      dz = g - centre_z;
      const double next = std::clamp(foot - (dx + s * dz) / (1 + s * s), far_lo, far_hi);
      if (std::abs(next - foot) <= 1e-15 * (1 + std::abs(foot))) {
        settled = true;
        break;
      }
      foot = next;
    }
    // Gauss–Newton leaves out the flank's curvature, g''·(g − z_c) in the distance's second
    // derivative: where the flank curves as tightly as the nose (a 0.3 mm nose over a
    // 0.3 mm lenslet) its steps overshoot by half and never settle, and the foot it ends
    // on is not the nearest point (a held nose 56 nm into that flank). Newton's steps then.
    for (int it = 0; !settled && it < 30; ++it) {
      double bend;
      if (!section.at(foot, g, s, bend)) return -R;
      dx = foot - centre_x;
      dz = g - centre_z;
      const double second = 1 + s * s + bend * dz;
      const double next =
          std::clamp(foot - (dx + s * dz) / (second > 0 ? second : 1 + s * s), far_lo, far_hi);
      settled = std::abs(next - foot) <= 1e-15 * (1 + std::abs(foot));
      foot = next;
    }
    return R - std::hypot(dx, dz);
  };
  // The held nose, its centre and own-flank values those last computed at a.
  const auto held_touch = [&](double a, double far_foot) {
    t.rho = a;
    t.z = g_a;
    t.slope = slope_a;
    t.centre_x = centre_x;
    t.centre_z = centre_z;
    t.held = true;
    t.crease_rho = crease;
    t.far_rho = far_foot;
    // The material left between the two touches, largest at a crease between them (on
    // each piece between, the nose's arc less the section is convex): the held one, and
    // those of a trough the nose spans.
    t.uncut = 0;
    bool lowest = true;
    for (int k = 0; k < creases.count; ++k) {
      if (k != held_at &&
          !(creases.rho[k] > std::min(a, far_foot) && creases.rho[k] < std::max(a, far_foot)))
        continue;
      // The hold is named by the lowest crease between its touches, whichever crease it
      // was solved at: a nose across a trough is one hold for every contact under it, its
      // touch on the flank of the contact's side of that crease, as at a single crease
      // (solved at the far rim for a contact on the near lenslet and at the near rim for
      // one on the flat, it had looked like two holds with one centre, and the chord
      // search took the touch's change for an error of 276 nm at any step).
      if (lowest) t.crease_rho = creases.rho[k];
      lowest = false;
      t.uncut = std::max(t.uncut,
                         left_at_crease(section, creases.rho[k], centre_x, centre_z, nose_radius));
    }
    return t;
  };
  const auto beyond_reach = [&](int k) {
    return k < 0 || k >= creases.count || !(std::abs(creases.rho[k] - crease) < 2 * R);
  };
  // The crease that ends the own flank away from the held one. The own flank is the piece
  // the contact lies on: where other creases lie between it and the held one, the nose
  // spans a trough (and was left unheld over the far flank when taken from the piece next
  // to the held crease).
  int next_crease = held_at - far;
  while (!beyond_reach(next_crease) && far * (creases.rho[next_crease] - rho_p) > kOffCrease) {
    piece_bounds(creases, next_crease, -far, crease - 2 * R, crease + 2 * R, near_lo, near_hi);
    next_crease -= far;
  }
  const double own = std::clamp(rho_p, near_lo, near_hi);
  // The root of F on the own flank [near_lo, near_hi], walking away from `origin` (where
  // F(a_in) = f_in > 0) until F < 0, then Illinois regula falsi. Where the flank ends at a
  // crease with the nose still overhanging, the trough is narrower than the nose: it
  // cannot reach that flank, and rests on the one beyond that crease (a microlens
  // array's flat between lenslets closer than the nose is wide). False: not resolved.
  const auto solve = [&](double a_in, double f_in, double origin, double step, double& a) {
    double a_out = a_in, f_out = f_in;
    for (;; step *= 2) {
      a_out = std::clamp(origin - far * step, near_lo, near_hi);
      f_out = F(a_out);
      if (f_out < 0) break;
      if (a_out == (far > 0 ? near_lo : near_hi) && !beyond_reach(next_crease)) {
        piece_bounds(creases, next_crease, -far, crease - 2 * R, crease + 2 * R, near_lo, near_hi);
        next_crease -= far;
        a_in = origin = far > 0 ? near_hi : near_lo;
        f_in = F(a_in);
        if (!(f_in > 0)) return false;  // the offsets meet in that crease's own turn
        step = 0.5e-4 * R;              // doubled before the next trial
        continue;
      }
      if (step > 2 * R || a_out == near_lo || a_out == near_hi) return false;
    }
    int kept = 0;
    a = a_in;
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
    return true;
  };
  NoseTouch held;
  // The nose at the contact itself overhangs the far flank by more than `tolerance`
  // (a point of that flank inside its circle): F(own) > 0, and F falls away
  // from the crease, so the root lies that way from `own`. Newton on the two offsets from
  // (own, the overhang's point) when it lands there; else (and for a clamped contact,
  // whose nose was not the one measured) the bracketing search.
  double a_newton = own, b_newton = overhang_rho;
  if (own == rho_p &&
      offsets_meet(section, R, far > 0 ? near_lo : own, far > 0 ? own : near_hi, far_lo, far_hi,
                   a_newton, b_newton, g_a, slope_a, centre_x, centre_z)) {
    held = held_touch(a_newton, b_newton);
  } else {
    double start = own, f_start = F(own), origin = crease,
           step = std::max(std::abs(crease - own), 1e-4 * R);
    if (!(f_start > 0)) {
      // A contact on the crease that ends its flank may carry the slope of the flank
      // beyond it (which one is a matter of rounding): its nose is that flank's offset,
      // which overhangs the far one across the trough. The hold is solved on that flank.
      if (beyond_reach(next_crease) || !(std::abs(creases.rho[next_crease] - rho_p) <= kOffCrease))
        return t;  // the overhang is not this flank's to resolve
      piece_bounds(creases, next_crease, -far, crease - 2 * R, crease + 2 * R, near_lo, near_hi);
      next_crease -= far;
      start = origin = far > 0 ? near_hi : near_lo;
      f_start = F(start);
      step = 1e-4 * R;
      if (!(f_start > 0)) return t;
    }
    double a;
    if (!solve(start, f_start, origin, step, a)) return t;
    held = held_touch(a, foot);
  }
  // The own flank's solution may overhang the flank beyond its other crease: a trough
  // narrower than the nose, whose two holds cross (each alone would put the nose into the
  // other side's flank; on a microlens array 21 µm). The nose then rests on the flanks
  // either side of the trough: solved again on the one beyond.
  for (int guard = 0; guard < 4 && !beyond_reach(next_crease); ++guard) {
    double lo, hi;
    piece_bounds(creases, next_crease, -far, crease - 2 * R, crease + 2 * R, lo, hi);
    NoseOverlap o;
    search(section, held.centre_x, held.centre_z, R, creases.rho[next_crease] - far * kOffCrease,
           lo, hi, 4, o, -far, m, tolerance);
    if (!(o.height > tolerance)) break;
    near_lo = lo;
    near_hi = hi;
    next_crease -= far;
    const double start = far > 0 ? near_hi : near_lo;
    const double f_start = F(start);
    double a;
    if (!(f_start > 0) || !solve(start, f_start, start, 1e-4 * R, a)) break;
    held = held_touch(a, foot);
  }
  return held;
}

// How far the centre must move across a ridge before the nose rolls over it: less is
// rounding of the flanks' slopes at kOffCrease either side (a smooth point listed as a
// crease), and a jump that small leaves chords a fraction of a picometre deep.
constexpr double kLeastRoll = 1e-9;  // mm
// A crease whose offset folds back by less than this fraction of R (its slope jumps by
// less) is taken for a smooth point where it could bound a ridge's window (ridge_windows).
constexpr double kSmoothRoll = 1e-6;
// A ridge's window reaches this fraction of R, and of the distance to the next crease
// that is no ridge (or to the axis), either side: so no window reaches a valley's, and
// every crease that can bound one lies within 1.45 R of a contact in it.
constexpr double kWindow = 0.45;

// The centre's abscissa on the offset of the section at a, a − R·g'/√(1 + g'²).
double offset_x(double a, double slope, double R) {
  return a - R * slope / std::sqrt(1 + slope * slope);
}

// How fast a flank's offset moves with its foot (slope s, bend g''), kept off 0 for the
// spread, which it divides.
double offset_rate(double s, double bend, double R) {
  const double l = std::sqrt(1 + s * s);
  return std::max(1 - R * bend / (l * l * l), 1e-6);
}

// The ridges' windows about a contact (nose_touch; docs/tool.md, "Ridges").
//
// Along the section the contact's own placement (its offset, or its hold) jumps forward
// at each ridge ρ_k by the roll J_k = x_out − x_in: the inner flank's offset at the ridge
// ends at x_in = ρ_k − R·s_in/√(1 + s_in²), the outer one's starts at x_out (s_in > s_out,
// the slope falling). Each ridge gets a window [ρ_k − w_in, ρ_k + w_out], w the lesser of
// kWindow·R and kWindow times the distance to the next crease that is no ridge (or to the
// axis), and across it the jump is spread into a ramp: the centre's abscissa is the
// contact's own plus Σ_k J_k·(ramp_k(ρ) − step_k(ρ)), continuous in the contact, and in θ
// while the rolls and windows are (a ridge appears with no roll, where a section grazes a
// rim). The window does not depend on the roll, so the ramps of ridges close together (two
// rims through one point, a land narrower than the nose) add up to the ramp of their
// joint roll as the ridges meet: their windows were the roll wide at first, and a section
// through the point where two bowls touch jumped between the two.
struct RidgeWindows {
  bool inside = false;  // the contact lies in a window
  double shift = 0;     // mm: Σ J_k (ramp_k − step_k) at the contact
  double rate = 0;      // Σ J_k / (w_in + w_out) over the windows it lies in
  // The contact lies within kOffCrease of a ridge, where its own placement may carry
  // either flank's slope or neither (two rims through one point, evaluated on the plane
  // between): it is placed from just inside the ridge instead, this contact.
  double on_ridge = std::numeric_limits<double>::quiet_NaN();
};

// ridge_windows: held_x(ρ, x) puts in x (the flank's offset there) the centre's abscissa where
// the contact's own placement at ρ, just beside a ridge, is held. A hold beside a ridge
// moves the jump: across a bowl tighter than the nose, between two rims, the placement
// jumps from the rim's offset to the nose resting on both rims (docs/tool.md, "Bowls
// tighter than the nose"), not to the bowl's own offset, and a ramp of the flanks' roll
// jumped back by the difference at the ridge (33 µm on a bowl of radius 0.15 mm under a
// 0.2 mm nose).
template <class HeldX>
RidgeWindows ridge_windows(const Section& section, const SectionCreases& creases, double R,
                           double rho_p, HeldX held_x) {
  RidgeWindows out;
  // The roll across the creases k..last (within 2·kOffCrease of each other: one crease,
  // two rims through one point), the slopes taken either side of the group.
  // The roll is x_out − x_in: the inner flank's offset ends at x_in, the outer one's
  // starts at x_out.
  const auto roll_across = [&](int k, int last, double& x_in, double& x_out) {
    double g, s_in, s_out;
    if (!section.at(creases.rho[k] - kOffCrease, g, s_in) ||
        !section.at(creases.rho[last] + kOffCrease, g, s_out))
      return false;
    x_in = offset_x(creases.rho[k], s_in, R);
    x_out = offset_x(creases.rho[k], s_out, R);
    return true;
  };
  const auto group_end = [&](int k) {
    while (k + 1 < creases.count && creases.rho[k + 1] - creases.rho[k] <= 2 * kOffCrease) ++k;
    return k;
  };
  // Most contacts near creases are near valleys alone: those within kWindow·R first.
  bool ridge_near = false;
  for (int k = 0; k < creases.count && !ridge_near; k = group_end(k) + 1) {
    double x_in, x_out;
    if (!(std::abs(creases.rho[k] - rho_p) < kWindow * R)) continue;
    if (!roll_across(k, group_end(k), x_in, x_out)) return out;
    ridge_near = x_out - x_in > kLeastRoll;
  }
  if (!ridge_near) return out;
  // Each crease within 1.45 R, with its roll: the ridges within kWindow·R and every crease
  // that can bound their windows.
  struct Crease {  // trivial: the buffer is not filled on every call
    double rho, last, x_in, x_out;
    double roll() const { return x_out - x_in; }
  };
  std::array<Crease, SectionCreases::kCapacity> near;
  int count = 0;
  for (int k = 0; k < creases.count; k = group_end(k) + 1) {
    double x_in, x_out;
    const int last = group_end(k);
    if (!(std::abs(creases.rho[k] - rho_p) < (1 + kWindow) * R)) continue;
    if (!roll_across(k, last, x_in, x_out)) return out;
    near[static_cast<std::size_t>(count++)] = {creases.rho[k], creases.rho[last], x_in, x_out};
  }
  const auto ridge = [&](int i) { return near[static_cast<std::size_t>(i)].roll() > kLeastRoll; };
  // A crease that bounds a ridge's window: a valley, where the nose may be held. A crease
  // across which the offset neither jumps nor folds back (a slope jump under a
  // millionth) is a point the view of troughs tighter than the nose lists on a smooth
  // piece (path/tight_troughs.hpp): its samples fall at whole steps of ρ, so it comes and
  // goes with θ, and a window it bounded would change its width at once from one section
  // to the next, the centre with it.
  const auto bounds_windows = [&](int i) {
    return !(near[static_cast<std::size_t>(i)].roll() > -kSmoothRoll * R);
  };
  for (int i = 0; i < count; ++i) {
    const Crease& c = near[static_cast<std::size_t>(i)];
    if (!ridge(i) || !(c.rho >= 0) || !(std::abs(c.rho - rho_p) < kWindow * R)) continue;
    // A ridge off the axis keeps its window on its own side of it. The axis's own ridge
    // (a cone's apex pointing at the tool) is the section's fold: the path's contacts
    // reach it from ρ > 0 alone, and halfway through its roll, at the axis itself, the
    // centre stands over the apex (on the axis where the apex is symmetric).
    double below = c.rho > 0 ? c.rho : std::numeric_limits<double>::infinity(),
           above = std::numeric_limits<double>::infinity();
    for (int j = i - 1; j >= 0; --j)
      if (bounds_windows(j)) {
        below = std::min(below, c.rho - near[static_cast<std::size_t>(j)].rho);
        break;
      }
    for (int j = i + 1; j < count; ++j)
      if (bounds_windows(j)) {
        above = near[static_cast<std::size_t>(j)].rho - c.rho;
        break;
      }
    const double start = c.rho - kWindow * std::min(R, below);
    const double end = c.rho + kWindow * std::min(R, above);
    if (!(rho_p > start && rho_p < end)) continue;
    if (!(std::abs(rho_p - c.rho) > kOffCrease)) {
      out.on_ridge = c.rho - 2 * kOffCrease;
      return out;
    }
    out.inside = true;
    // Beside a held placement, its centre in place of the flank's offset.
    double x_in = c.x_in, x_out = c.x_out;
    held_x(c.rho - kOffCrease, x_in);
    held_x(c.last + kOffCrease, x_out);
    const double roll = x_out - x_in;
    out.shift += roll * ((rho_p - start) / (end - start) - (rho_p > c.rho ? 1.0 : 0.0));
    out.rate += roll / (end - start);
  }
  return out;
}

// The nose of radius R centred at abscissa x_c dropped onto the section (the drop-cutter):
// the section's highest point over the lower arc of the nose about (x_c, z_ref), as
// nose_overlap finds it from `hint`, made exact at a crease (the searches start kOffCrease
// off each crease, a few 1e-11 mm below a ridge's peak, and the section's value at the
// crease itself, its height both flanks', makes the touch there exact) and on a flank
// (nose_overlap settles the peak to 1 pm; Newton's steps with the flank's own curvature,
// h'' = g'' − R²/s³, take it to rounding, so that the dropped nose is not that far into the
// design; a step that would cross a crease is not taken). `creases` must hold every crease
// within R of x_c. at_crease: the touch lies at (or within 1e-12 mm of) a crease.
NoseOverlap drop_onto_section(const Surface& design, const Section& section,
                              const SectionCreases& creases, const RadialLine& line, double x_c,
                              double z_ref, double R, double hint, bool& at_crease) {
  at_crease = false;
  // More creases than a list holds, under the nose or about it: no drop is made.
  if (!creases.covers(x_c - R, x_c + R)) return NoseOverlap{};
  NoseOverlap o = nose_overlap(design, line, x_c, z_ref, R, hint);
  if (o.height == std::numeric_limits<double>::infinity()) return NoseOverlap{};
  for (int k = 0; k < creases.count; ++k) {
    const double d = creases.rho[k] - x_c;
    double g, s;
    if (!(std::abs(d) < 0.999 * R) || !section.at(creases.rho[k], g, s)) continue;
    const double h = g - z_ref + std::sqrt(R * R - d * d);
    if (h >= o.height - 1e-12) at_crease = true;
    if (h > o.height) o.height = h, o.rho = creases.rho[k];
  }
  for (int it = 0; it < 3 && !at_crease; ++it) {
    double g, s, bend;
    const double d = o.rho - x_c, arc = std::sqrt(R * R - d * d);
    if (!section.at(o.rho, g, s, bend) || !(arc > 0)) break;
    const double h_slope = s - d / arc, h_bend = bend - R * R / (arc * arc * arc);
    if (!(h_bend < 0)) break;
    const double next = o.rho - h_slope / h_bend;
    bool crosses = false;
    for (int k = 0; k < creases.count; ++k)
      crosses = crosses || (creases.rho[k] - o.rho) * (creases.rho[k] - next) <= 0;
    double g_next, s_next;
    if (crosses || !section.at(next, g_next, s_next)) break;
    const double d_next = next - x_c;
    if (!(std::abs(d_next) < R)) break;
    const double h = g_next - z_ref + std::sqrt(R * R - d_next * d_next);
    if (!(h > o.height)) break;
    o.height = h;
    o.rho = next;
  }
  return o;
}

// The nose over the ridges' windows (nose_touch): the contact's own placement moved along
// the section by windows.shift and dropped onto the design there (drop_onto_section),
// touching it at the section's highest point over the nose's lower arc. The slope handed
// on is the nose's tangent at the touch (at a ridge, no flank's), so that the offset along
// it is the centre. False where the section is undefined.
bool roll_over_ridges(const Surface& design, const Section& section, const SectionCreases& creases,
                      const RadialLine& line, double R, double rho_p, const RidgeWindows& windows,
                      NoseTouch& t) {
  const double x_c = t.centre_x + windows.shift;
  bool at_crease;
  const NoseOverlap o =
      drop_onto_section(design, section, creases, line, x_c, t.centre_z, R, rho_p, at_crease);
  const double d = o.rho - x_c, rise = std::sqrt(std::max(R * R - d * d, 0.0));
  if (!(o.height > -1e300) || !(rise > 0)) return false;
  const double z_c = t.centre_z + o.height;
  // How far the touches of neighbouring passes spread: the centre moves (the contact's own
  // offset's rate + the windows') per unit of contact, the touch 1/(its offset's rate) as
  // far as the centre; at a ridge, the slower of its flanks.
  double g, s, bend;
  if (!section.at(rho_p, g, s, bend)) return false;
  const double centre_rate = offset_rate(s, bend, R) + windows.rate;
  double touch_rate = 1e300;
  for (const double side : {-1.0, 1.0}) {
    if (!section.at(o.rho + side * kOffCrease, g, s, bend)) return false;
    touch_rate = std::min(touch_rate, offset_rate(s, bend, R));
  }
  t.rolling = true;
  t.at_ridge = at_crease;
  t.held = false;
  t.uncut = 0;
  t.rho = o.rho;
  t.z = z_c - rise;
  t.slope = d / rise;
  t.centre_x = x_c;
  t.centre_z = z_c;
  t.spread = centre_rate / touch_rate;
  return true;
}

// The hold found from the nose's overhang of the whole section, for a section with no
// concavity bound where the creases' own holds leave the nose overhanging (a trough
// tighter than the nose whose tight stretch is wide, a nose wider than the troughs' period,
// path/tight_troughs.hpp, or a bowl tighter than the nose between two rims). A contact whose
// own offset overhangs the section somewhere (nose_overlap) is one the nose never touches:
// it lies in a gap of the envelope. The nose dropped onto the section at abscissa x
// (drop_onto_section) touches it at ρ*(x), which never falls as x grows (a circle's
// translates' upper envelope), and jumps across each gap: the hold is the drop at the x*
// where ρ* passes the contact, the centre from which the nose touches both sides of the
// gap, whatever they are (flanks, or ridges the nose rolls over). Found by doubling steps
// from the contact, then bisection to rounding, so that every contact of one held region
// gives the same centre. Walking the contact's own offset along its side to the first one
// that overhangs nothing, as before December 2026, found the same point on a smooth
// trough, but between two rims no offset of the bowl overhangs nothing, and the walk ended
// on the rim: a nose there is still rolling, and the contacts beyond were placed 22 µm
// into the bowl's far wall. t (unheld) where no such x lies within 2R.
NoseTouch hold_by_overhang(const Surface& design, const Section& section, const RadialLine& line,
                           NoseTouch t, double rho_p, double R, double nose_radius,
                           double tolerance) {
  const NoseOverlap first = nose_overlap(design, line, t.centre_x, t.centre_z, R, rho_p);
  if (!(first.height > tolerance) || !std::isfinite(first.height)) return t;
  // The drops reach 2R either side of the contact, each over R about itself. Where the
  // section meets more creases there than a list holds, a narrower stretch: the drops
  // beyond it are not made (drop_onto_section), and a gap wider than it is not held here.
  SectionCreases creases;
  for (double reach = 3 * R;; reach *= 0.75)
    if (creases.find(design, line, rho_p - reach, rho_p + reach) || reach < 1.2 * R) break;
  const double z_ref = t.centre_z;
  // The drop at x: its touch, and the height it lifts the nose by from z_ref.
  const auto drop = [&](double x, NoseOverlap& o, bool& at_crease) {
    o = drop_onto_section(design, section, creases, line, x, z_ref, R,
                          std::clamp(rho_p, x - 0.999 * R, x + 0.999 * R), at_crease);
    return o.height > -1e300;
  };
  NoseOverlap o;
  bool before_on_crease = false, after_on_crease = false;
  if (!drop(rho_p, o, before_on_crease)) return t;
  // x below the crossing where the touch lies below the contact, above it where not.
  const double toward = o.rho < rho_p ? 1.0 : -1.0;
  double before = rho_p, after = rho_p;
  NoseOverlap touch_before = o, touch_after;
  // Doubling from a twentieth of R: a bowl's far rim lies a few such steps off, and the
  // bracket's width costs the bisection only its logarithm (from a thousandth of R, the
  // doubling had been a fifth of a tight bowl's plan).
  for (double step = 0.05 * R;; step *= 2) {
    if (step > 2 * R) return t;
    after = rho_p + toward * step;
    if (!drop(after, touch_after, after_on_crease)) return t;
    if ((touch_after.rho - rho_p) * toward >= 0) break;
    before = after;
    touch_before = touch_after;
    before_on_crease = after_on_crease;
  }
  // Where both touches lie on creases (a bowl's two rims), the nose resting on both has its
  // centre at the upper crossing of the circles of radius R about them, in closed form. It
  // stands where it lies in the bracket and the drop there finds nothing higher; then the
  // bisection's fifty drops are two.
  double x = after, z_c = z_ref + touch_after.height;
  bool closed = false;
  double tried_below = std::numeric_limits<double>::quiet_NaN(), tried_above = tried_below;
  const auto rest_on_creases = [&] {
    if (!(before_on_crease && after_on_crease) || touch_before.rho == touch_after.rho ||
        (touch_before.rho == tried_below && touch_after.rho == tried_above))
      return false;
    tried_below = touch_before.rho;
    tried_above = touch_after.rho;
    double g_a, g_b, slope;
    if (!section.at(touch_before.rho, g_a, slope) || !section.at(touch_after.rho, g_b, slope))
      return false;
    const double vx = touch_after.rho - touch_before.rho, vz = g_b - g_a;
    const double d = std::hypot(vx, vz);
    if (!(d < 2 * R)) return false;
    const double h = std::sqrt(R * R - 0.25 * d * d), up = vx > 0 ? 1.0 : -1.0;
    const double cx = 0.5 * (touch_before.rho + touch_after.rho) - up * h * vz / d;
    const double cz = 0.5 * (g_a + g_b) + up * h * vx / d;
    if (!((cx - before) * toward > 0 && (after - cx) * toward > 0)) return false;
    NoseOverlap check;
    bool on_crease;
    if (!drop(cx, check, on_crease) || !(check.height <= cz - z_ref + 1e-12)) return false;
    x = cx;
    z_c = cz;
    return true;
  };
  for (int it = 0; it < 200 && std::abs(after - before) > 1e-14 * (1 + std::abs(before)); ++it) {
    if ((closed = rest_on_creases())) break;
    const double mid = 0.5 * (before + after);
    if (mid == before || mid == after) break;
    NoseOverlap m;
    bool on_crease;
    if (!drop(mid, m, on_crease)) return t;
    if ((m.rho - rho_p) * toward >= 0) {
      after = mid;
      touch_after = m;
      after_on_crease = on_crease;
    } else {
      before = mid;
      touch_before = m;
      before_on_crease = on_crease;
    }
  }
  // The nose at the crossing's upper end: it touches the section there, and its other
  // touch (the one just below the crossing) to rounding.
  const double below_touch = toward > 0 ? touch_before.rho : touch_after.rho;
  const double above_touch = toward > 0 ? touch_after.rho : touch_before.rho;
  const bool below_on_crease = toward > 0 ? before_on_crease : after_on_crease;
  const bool above_on_crease = toward > 0 ? after_on_crease : before_on_crease;
  // The touch on the side away from the contact's deepest overhang is its own (the nose
  // rests on the far side of the gap from the overhang as on the near one of a crease).
  const bool own_below = first.rho > rho_p;
  const double own = own_below ? below_touch : above_touch;
  const bool own_on_crease = own_below ? below_on_crease : above_on_crease;
  const double far_touch = own_below ? above_touch : below_touch;
  if (!closed) {
    x = after;
    z_c = z_ref + touch_after.height;
  }
  const double d = own - x, rise = std::sqrt(std::max(R * R - d * d, 0.0));
  double g, slope;
  if (!(rise > 0) || !section.at(own, g, slope)) return t;
  NoseTouch held = t;
  held.rho = own;
  held.z = z_c - rise;
  held.slope = d / rise;  // the nose's tangent at the touch: the offset along it is x
  held.centre_x = x;
  held.centre_z = z_c;
  held.held = true;
  held.at_ridge = own_on_crease;
  held.far_rho = far_touch;
  // The material left between the two touches, at the creases between them (the bottoms
  // of the troughs the view lists, and any real crease), as the crease's hold measures it.
  held.uncut = 0;
  held.crease_rho = 0.5 * (below_touch + above_touch);
  bool lowest = true;
  for (int k = 0; k < creases.count; ++k) {
    if (!(creases.rho[k] > below_touch && creases.rho[k] < above_touch)) continue;
    if (lowest) held.crease_rho = creases.rho[k];
    lowest = false;
    held.uncut = std::max(held.uncut, left_at_crease(section, creases.rho[k], x, z_c, nose_radius));
  }
  return held;
}

// Without a concavity bound (m ≤ 0) a piece may bend more tightly than the nose over part of
// it (a trough barely tighter than the nose, whose stretch path/tight_troughs.hpp lists with
// its ends where the section is not tight): the nose's height over it is then convex there,
// and a search from the crease at that end can start at its least value, take it for a
// peak, and miss the peak beyond (a nose 2.3 µm into a sinusoidal grid's far flank). The
// piece [a, b] searched from the crease on `side` of it is searched from its other end too.
void search_from_far_end(const Section& section, double x_c, double z_c, double R, double a,
                         double b, int side, double m, double up, double tolerance,
                         NoseOverlap& best) {
  if (m > 0) return;
  search(section, x_c, z_c, R, side > 0 ? b : a, a, b, 4, best, -side, m, tolerance, nullptr, up);
}

// A piece [a, b] searched for an overhang of more than `tolerance`: from the crease on
// `side` of it and, without a concavity bound, from its other end, unless the first value's
// parabola (search's `up`) already keeps the whole piece below the tolerance. On hexagonal
// bowls whose walls bend 3 % more than a 0.107 mm nose, the searches from the far end were
// 40 % of the run.
void search_piece(const Section& section, double x_c, double z_c, double R, double crease, double a,
                  double b, int side, double m, double up, double tolerance, NoseOverlap& best) {
  if (search(section, x_c, z_c, R, crease + side * kOffCrease, a, b, 4, best, side, m, tolerance,
             nullptr, up))
    return;
  search_from_far_end(section, x_c, z_c, R, a, b, side, m, up, tolerance, best);
}

// The contact's own placement (nose_touch without the ridges): its offset t, or the nose
// held at a concave crease where that would overhang one.
NoseTouch offset_or_hold(const Surface& design, const Section& section, const RadialLine& line,
                         const SectionCreases& creases, NoseTouch t, double rho_p, double R,
                         double nose_radius, double tolerance) {
  const double reach = 0.999 * R;
  // Every flank the nose overhangs, and the crease of the one it overhangs most.
  struct Candidate {  // trivial: the buffer is not filled on every call
    int crease, side;
    double height, rho;
  };
  std::array<Candidate, 2 * SectionCreases::kCapacity> overhung;
  int held_at = -1, far = 0, count = 0;
  NoseOverlap worst;
  worst.height = tolerance;
  const double radius = std::max(std::abs(t.centre_x - reach), std::abs(t.centre_x + reach));
  // Named, not bound by `auto [m, up]`: the lambdas below capture them, which Clang before
  // 16 refuses for structured bindings.
  const PieceBend bend = piece_bend(design, R, radius);
  const double m = bend.m, up = bend.up;
  for (int k = 0; k < creases.count; ++k) {
    if (!(std::abs(creases.rho[k] - t.centre_x) < reach) &&
        !(std::abs(creases.rho[k] - rho_p) <= kOffCrease))
      continue;
    // The far flank is the one across the crease from the contact. A contact within
    // kOffCrease of the crease may carry either flank's slope (which one the design
    // evaluated there is a matter of rounding), so both are searched: the one it does
    // not carry is overhung. Taking the far side from the contact's position alone left
    // such a nose unheld, over the other flank.
    const bool at_crease = std::abs(creases.rho[k] - rho_p) <= kOffCrease;
    for (const int side : {-1, 1}) {
      if (!at_crease && side != (creases.rho[k] > rho_p ? 1 : -1)) continue;
      double a, b;
      piece_bounds(creases, k, side, t.centre_x - reach, t.centre_x + reach, a, b);
      NoseOverlap o;
      // Searched to the tolerance, not to the worst so far: every overhung flank is kept,
      // to check the hold against and to hold at instead (below).
      search_piece(section, t.centre_x, t.centre_z, R, creases.rho[k], a, b, side, m, up, tolerance,
                   o);
      if (o.height > tolerance)
        overhung[static_cast<std::size_t>(count++)] = {k, side, o.height, o.rho};
      if (o.height > worst.height) {
        worst = o;
        held_at = k;
        far = side;
      }
    }
  }
  if (held_at < 0) {
    // Nothing overhung by the tolerance. Without a concavity bound the contact itself may
    // lie where the section bends more tightly than the nose, on a stretch barely tighter
    // (path/tight_troughs.hpp) whose overhang stays under the tolerance: no nose touches
    // there without cutting into the design, and the local gouge check refused such a job
    // (a sinusoidal grid bending to 1.49987 mm under a 1.5 mm nose). The nose is held at
    // the crease nearest the contact instead, across it from the contact.
    if (m > 0 || !(radial_section_curvature(design, line, rho_p) * R > 1)) return t;
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < creases.count; ++k) {
      const double d = std::abs(creases.rho[k] - rho_p);
      if (d < nearest && d < reach) nearest = d, held_at = k;
    }
    if (held_at < 0) return t;
    far = creases.rho[held_at] > rho_p ? 1 : -1;
    worst.rho = creases.rho[held_at] + far * kOffCrease;
  }
  const NoseTouch held = hold_at_crease(section, creases, t, rho_p, R, nose_radius, m, tolerance,
                                        held_at, far, worst.rho);
  // Without a concavity bound the pieces between creases may bend more than the nose (a
  // trough tighter than it, listed as creases by path/tight_troughs.hpp): a hold solved
  // on a crease's flanks can still overhang the section, or none may be found, and the
  // whole section's overhang places the nose instead (hold_by_overhang).
  const bool unbounded = !(m > 0);
  const auto by_overhang = [&](const NoseTouch& otherwise) {
    const NoseTouch h =
        hold_by_overhang(design, section, line, t, rho_p, R, nose_radius, tolerance);
    return h.held ? h : otherwise;
  };
  if (!held.held) return unbounded ? by_overhang(held) : held;
  // The hold at the crease overhung most may still overhang another flank: the nose held
  // at a lenslet's far rim, across a flat to the next lenslet, sank into the flat (3.8 µm
  // on a microlens array whose gaps are narrower than the nose). The envelope is the hold
  // that overhangs nothing: the other overhung creases' holds are tried, the most first.
  // Whether a held nose overhangs any piece of the section by more than the tolerance:
  // each piece under it searched from a crease that bounds it (the creases found reach 2R
  // past the contact and the offset, so past every held nose too); a piece that cannot
  // rise to the tolerance is left after one value. The piece of its own touch is not: the
  // nose is the offset of that touch, tangent there, and h is strongly concave on the
  // piece, so its one peak is the touch. The far touch is a foot found by iteration, and
  // its piece is searched like the rest.
  const auto overhangs = [&](const NoseTouch& h) {
    // The bounds over the held nose's reach as well as the contact's.
    const double radius_h =
        std::max({radius, std::abs(h.centre_x - reach), std::abs(h.centre_x + reach)});
    const PieceBend bend_h = radius_h > radius ? piece_bend(design, R, radius_h) : bend;
    for (int k = 0; k < creases.count; ++k) {
      if (!(std::abs(creases.rho[k] - h.centre_x) < reach)) continue;
      for (const int side : {-1, 1}) {
        // The piece below the first crease under the nose from its lower side; the others
        // from their lower crease.
        if (side < 0 && k > 0 && std::abs(creases.rho[k - 1] - h.centre_x) < reach) continue;
        double a, b;
        piece_bounds(creases, k, side, h.centre_x - reach, h.centre_x + reach, a, b);
        // A touch strictly inside: one at a piece's end may be a crease's corner (a foot
        // clamped there), which says nothing of the rest of the piece.
        const auto holds = [&](double rho) { return rho > a && rho < b; };
        if (holds(h.rho)) continue;
        NoseOverlap o;
        search_piece(section, h.centre_x, h.centre_z, R, creases.rho[k], a, b, side, bend_h.m,
                     bend_h.up, tolerance, o);
        if (o.height > tolerance) return true;
      }
    }
    return false;
  };
  // A nose that overhung one flank alone, with no more than one other crease under it, is
  // held clear of the rest (the trough on its own side is checked in hold_at_crease);
  // checking every hold cost 7 % of the compound eye's chord cut, whose holds never needed
  // another crease. A nose wider than the lenslets is not: held between two, it reached
  // into a third's crest (84 nm into domes 0.2 mm apart under a 3 mm nose), and the chord
  // rule stopped there.
  if (unbounded) return overhangs(held) ? by_overhang(held) : held;
  const auto creases_under = [&](const NoseTouch& h) {
    int under = 0;
    for (int k = 0; k < creases.count; ++k) under += std::abs(creases.rho[k] - h.centre_x) < reach;
    return under;
  };
  if (count < 2 && creases_under(held) <= 2) return held;
  if (!overhangs(held)) return held;
  std::sort(overhung.begin(), overhung.begin() + count,
            [](const Candidate& a, const Candidate& b) { return a.height > b.height; });
  for (int i = 0; i < count; ++i) {
    const Candidate& c = overhung[static_cast<std::size_t>(i)];
    if (c.crease == held_at && c.side == far) continue;
    const NoseTouch other = hold_at_crease(section, creases, t, rho_p, R, nose_radius, m, tolerance,
                                           c.crease, c.side, c.rho);
    if (other.held && !overhangs(other)) return other;
  }
  // None overhangs nothing: the whole section's overhang finds the gap the contact lies in
  // (its nose rests on the pieces either side of it, whichever they are); where it finds
  // none, the chord's measure sees the hold in the design, and the planner says so.
  return by_overhang(held);
}

}  // namespace

namespace {

// nose_touch and nose_roll: the contact's own placement held at concave creases or not,
// and rolled over ridges.
NoseTouch place_nose(const Surface& design, const RadialLine& line, double nose_radius,
                     double rho_p, double z_p, double slope_p, double stand_off, double tolerance,
                     bool hold) {
  const double R = nose_radius + stand_off;  // the envelope's radius
  NoseTouch t;
  t.rho = rho_p;
  t.z = z_p;
  t.slope = slope_p;
  const double length = std::sqrt(1 + slope_p * slope_p);
  t.centre_x = rho_p - R * slope_p / length;
  t.centre_z = z_p + R / length;
  if (!(R > 0) || !design.has_creases()) return t;
  const Section section(design, line);
  SectionCreases creases;
  // Every crease within 2R: those under the nose may be overhung, and the ones beyond bound
  // the flanks the held nose is solved on (a flank ends at the next crease).
  const double lo = std::min(rho_p, t.centre_x) - 2 * R, hi = std::max(rho_p, t.centre_x) + 2 * R;
  // More creases within reach than a list holds: the offset, which the chord's measure
  // (nose_overlap) sees into the design wherever it overhangs a crease.
  if (!creases.find(design, line, lo, hi)) return t;
  const auto own_placement = [&](const NoseTouch& offset, double contact) {
    return hold ? offset_or_hold(design, section, line, creases, offset, contact, R, nose_radius,
                                 tolerance)
                : offset;
  };
  // Within a ridge's window the nose rolls over it instead of jumping across.
  if (!design.may_have_ridges()) return own_placement(t, rho_p);
  // Where the section has no concavity bound (a trough tighter than the nose, listed by
  // path/tight_troughs.hpp), the placement beside a ridge may be held (ridge_windows).
  const bool unbounded = hold && !(section_concavity(design, R, std::abs(rho_p) + 3 * R) > 0);
  const auto flanks_only = [](double, double&) {};
  RidgeWindows windows = ridge_windows(section, creases, R, rho_p, flanks_only);
  if (!std::isnan(windows.on_ridge)) {
    rho_p = windows.on_ridge;
    if (!section.at(rho_p, t.z, t.slope)) return t;
    const double l = std::sqrt(1 + t.slope * t.slope);
    t.rho = rho_p;
    t.centre_x = rho_p - R * t.slope / l;
    t.centre_z = t.z + R / l;
    windows = ridge_windows(section, creases, R, rho_p, flanks_only);
  }
  const NoseTouch placed = own_placement(t, rho_p);
  const auto held_x = [&](double rho, double& x) {
    // A point inside the contact's own hold's gap (between its two touches) is held at
    // the same centre: the contact's hold stands for it, and is not searched again.
    if (placed.held && rho > std::min(placed.rho, placed.far_rho) &&
        rho < std::max(placed.rho, placed.far_rho)) {
      x = placed.centre_x;
      return;
    }
    NoseTouch side;
    if (!section.at(rho, side.z, side.slope)) return;
    const double l = std::sqrt(1 + side.slope * side.slope);
    side.rho = rho;
    side.centre_x = rho - R * side.slope / l;
    side.centre_z = side.z + R / l;
    SectionCreases near;
    const double lo = std::min(rho, side.centre_x) - 2 * R,
                 hi = std::max(rho, side.centre_x) + 2 * R;
    if (!near.find(design, line, lo, hi)) return;
    const NoseTouch h =
        offset_or_hold(design, section, line, near, side, rho, R, nose_radius, tolerance);
    if (h.held) x = h.centre_x;
  };
  if (unbounded && windows.inside) windows = ridge_windows(section, creases, R, rho_p, held_x);
  NoseTouch rolled = placed;
  if (windows.inside && roll_over_ridges(design, section, creases, line, R, rho_p, windows, rolled))
    return rolled;
  return placed;
}

}  // namespace

NoseTouch nose_touch(const Surface& design, const RadialLine& line, double nose_radius,
                     double rho_p, double z_p, double slope_p, double stand_off, double tolerance) {
  return place_nose(design, line, nose_radius, rho_p, z_p, slope_p, stand_off, tolerance, true);
}

NoseTouch nose_roll(const Surface& design, const RadialLine& line, double nose_radius, double rho_p,
                    double z_p, double slope_p, double stand_off) {
  return place_nose(design, line, nose_radius, rho_p, z_p, slope_p, stand_off, 0.0, false);
}

}  // namespace freeturn
