#pragma once
// The nose against the design's radial section, where the surface creases (docs/tool.md,
// "The envelope").
//
// In the radial plane at θ the design is the section g(ρ) = f(ρ cos θ, ρ sin θ) over signed
// ρ (ρ < 0 lies at θ + π, so the section runs through the axis), and the nose is a circle
// of radius R about its centre (x_c, z_c). The tool is safe where the section stays under
// the nose's lower arc, z_c − √(R² − (ρ − x_c)²), across the arc's footprint.
//
// Along a smooth section the nose tangent at the contact p, its centre p + R·n̂_p, is safe
// wherever the concave curvature stays below 1/R. At a concave crease (a lenslet rim, a
// cone's vertex) it is not: for contacts within about R·tan(δ/2) of a crease of angle δ the
// nose on one flank overhangs the other. There the nose is held where it touches both
// flanks, at the intersection of the two flanks' offsets: its centre moves continuously
// from one offset to the other through that point, never below the design, and the
// material between the two touches is left (the uncut residual).

#include <algorithm>
#include <array>

#include "freeturn/surface/surface.hpp"

namespace freeturn {

// Creases along one radial section (Surface::section_creases), in a fixed buffer. Only the
// first `count` are ever read, and the buffer is left unfilled: zeroing it was 7 to 10 % of
// the nose searches' own time (every sample near a rim makes one). Where the section meets
// more creases than the buffer holds (a nose many lenslets wide), the list holds the lowest
// and says how far it is whole: a placement or a measure that needs a crease beyond it is
// not made from it (path/section_envelope.cpp).
struct SectionCreases {
  static constexpr int kCapacity = 256;
  std::array<double, kCapacity> rho;
  int count = 0;
  // The list holds every crease in [lo, hi]: the stretch asked for, or, where the section
  // met more creases there than the buffer holds, up to the last one listed. Empty (lo >
  // hi) where the surface could not say.
  double lo = 0, hi = -1;

  // Those in [lo_asked, hi_asked] on the radial line at θ; whether the list holds them all.
  bool find(const Surface& design, const RadialLine& line, double lo_asked, double hi_asked) {
    const int found = design.section_creases(line, lo_asked, hi_asked, rho);
    count = std::clamp(found, 0, kCapacity);
    lo = lo_asked;
    hi = found < 0 ? lo_asked - 1 : found > kCapacity ? rho[kCapacity - 1] : hi_asked;
    return covers(lo_asked, hi_asked);
  }

  // Whether the list holds every crease in [a, b].
  bool covers(double a, double b) const { return a >= lo && b <= hi; }
};

// How strongly h(ρ) = g(ρ) − z_c + √(R² − (ρ − x_c)²), the section's height over the lower
// arc of a nose of radius R, is concave on a smooth piece of the section within `radius`
// of the axis: h'' = g'' − R²/s³ ≤ B − 1/R (s ≤ R), so m = 1/R − B (1/mm), B the design's
// Surface::max_section_bend (the nose's sections are radial).
// 0 where that is not positive or not known: nothing may be assumed of h then.
double section_concavity(const Surface& design, double R, double radius);

// How far the section reaches above the nose's lower arc.
struct NoseOverlap {
  double height = -1e300;  // mm, vertical: > 0 the nose is below the design (a gouge)
  double rho = 0;          // where (signed radius)
  double slope = 0;        // the section's slope dg/dρ there
};

// The largest height of the section above the lower arc of the nose centred at (x_c, z_c)
// (radius R > 0) in the radial plane at θ: from a local search started at hint_rho (the
// contact nearby) and, on each side of every crease under the nose, from the crease. Each
// search takes Newton steps on h(ρ) = g(ρ) − z_c + √(R² − (ρ − x_c)²) with the arc's
// −R²/s³ standing in for h'', keeps the largest value it meets (a value of h, so never
// more than the true maximum), and stays on its side of the crease. A piece whose values
// already met bound its top (its concavity, section_concavity) to within 1e-13 mm of the
// largest found is not searched again: the answer may be that much short of what the
// searches would find. Where no such bound settles the hint's piece (a section with no
// crease, or no concavity bound), its search goes on by secant steps until the peak they
// predict lies within 1 pm: with a design bending nearly as much as the nose, the arc's
// h'' alone left the peak tens of nanometres short (docs/path.md). No allocation.
NoseOverlap nose_overlap(const Surface& design, const RadialLine& line, double x_c, double z_c, double R,
                         double hint_rho);

// The same search from hint_rho alone, with no crease search: the overlap nose_overlap
// finds wherever touch_clear_of_creases holds at the touch (NoseOverlap::rho).
NoseOverlap nose_overlap_near(const Surface& design, const RadialLine& line, double x_c, double z_c,
                              double R, double hint_rho);

// Whether a nose of radius R (or less) whose lower arc is highest over the section at the
// point (x, y) of the design, on a smooth piece, can be sure to be highest there over every
// piece: no crease within its reach lets the section rise to it elsewhere. The creases'
// bounds (Surface::creases_near), each distance less `margin` (mm: how far the touch may
// move from (x, y) while this answer stands), against the envelope
//   h(t) − h(0) ≤ −m t²/2 + Σ_k n_k J_k (t − d_k)₊,  0 < t ≤ 2R,
// along the section either way from the touch, h the section's height over the arc
// (h'(0) = 0 at the touch), m = 1/R − max_section_bend how strongly concave h is on a smooth piece,
// and crease k at least d_k away with a slope jump of at most J_k, crossed at most n_k
// times. The right side is piecewise a concave parabola; true when it stays below 0
// throughout. Where that fails and the creases say how their rims lie (NearbyCrease's
// normal), it is tried again with each jump J_k scaled by a bound of |cos ψ|, ψ the angle
// between the sections and the rim's normal where they may cross it (docs/path.md, "The
// rims' directions"): the plain test first, so this only adds touches. On such a touch no
// crease search can find more (nose_overlap), and a nose touching there is not held
// (nose_touch). False where the surface cannot say.
bool touch_clear_of_creases(const Surface& design, double x, double y, double R, double margin);

// Whether every section the nose of radius R measures over the annulus [inner, outer] meets
// no more creases under it than a list holds (SectionCreases::kCapacity): nose_overlap
// takes the nose to be in the design where it does, and the chord rule stops there, after
// planning everything before it (minutes on a fine array). Sampled on 32 radial lines,
// radii R/2 apart (at most 512 of them); false, and (r, θ) where, at the first such
// section found.
bool crease_lists_whole_under_nose(const Surface& design, double R, double inner, double outer,
                                   double& r, double& theta);

// Where the nose touches the section for the contact at signed radius rho_p.
struct NoseTouch {
  double rho = 0, z = 0, slope = 0;   // the touch on the contact's own flank, and dg/dρ there
  double centre_x = 0, centre_z = 0;  // the nose centre in the radial plane
  bool held = false;      // held at a crease: touching both flanks, the contact not reached
  double crease_rho = 0;  // the crease it is held at (held only)
  double far_rho = 0;     // the touch on the other flank (held only)
  double uncut = 0;       // mm: material left above the crease, vertical (held only)
  // Rolling over a ridge (a convex crease, where the section's slope falls): the contact
  // lies in a ridge's window, across which the centre moves along the envelope from one
  // flank's offset, over the arc of radius R about the ridge, to the other's, instead of
  // jumping across the ridge (every chord over a jump cuts into the ridge). `slope` is
  // then the nose's tangent at the touch, not the design's, so that the offset along it
  // is the centre (at the ridge itself no flank's slope is).
  bool rolling = false;
  // The touch lies on a ridge (rolling over it, or resting on it with the nose held across
  // a bowl tighter than itself): `slope` is the nose's tangent there, and the section bends
  // away from the nose at the corner whatever its flanks' curvature.
  bool at_ridge = false;
  // How far apart the touches of neighbouring passes lie, per unit of their contacts'
  // spacing (rolling only, else 1): the window moves the centre faster than the contact,
  // and a flank's offset moves 1 − R·κ times as fast as its foot (κ the section's
  // curvature, > 0 concave), so the touches spread and the scallop between them grows. At
  // a ridge, the slower of its two flanks'.
  double spread = 1;
};

// The ordinary offset p + R·n̂_p of the contact (rho_p, z_p) with section slope slope_p, or,
// where the nose there would overhang a crease's other flank by more than `tolerance`
// (mm), the nose held at that crease: its centre at the intersection of the two flanks'
// offsets, found as the point of the contact's own flank whose offset lies exactly R
// from the other flank (Illinois regula falsi on R − distance, the distance by
// Gauss–Newton on the foot point). No allocation.
//
// With a stand-off h > 0 the nose of radius R is placed as the envelope of a nose of
// radius R + h (its centre p + (R + h)·n̂_p, held where that larger nose would overhang),
// so every point of it stays at least h above the design; `uncut` is still measured
// under the real nose.
//
// Where the contact lies within a ridge's window (docs/tool.md, "Ridges"), the centre is
// the placement above moved along the section so that it ramps across the ridge's roll
// instead of jumping (w either side: the lesser of 0.45 R and 0.45 of the distance to the
// next crease that is no ridge, or the axis; the ramps of ridges close together add up),
// and dropped onto the design there: it touches the section's highest
// point under the nose's lower arc (nose_overlap), a flank or the ridge.
NoseTouch nose_touch(const Surface& design, const RadialLine& line, double R, double rho_p, double z_p,
                     double slope_p, double stand_off = 0, double tolerance = 1e-10);

// nose_touch for a nose whose B axis follows the normal: rolled over ridges the same way,
// and held nowhere. Its edge point that touches is fixed on the tool (B turns with the
// touch's normal), which a hold, touching two flanks away from it, is not; a rolling nose
// touches the ridge, and B turns with the nose's tangent there.
NoseTouch nose_roll(const Surface& design, const RadialLine& line, double R, double rho_p,
                    double z_p, double slope_p, double stand_off = 0);

}  // namespace freeturn
