#pragma once
// Simulating the cut (paper 001's promise: the form error known before cutting).
//
// The tool nose, a circle of radius R in the radial plane at the spindle angle (in the
// rake plane h off the spindle line, with a centre height: sweep_rake_plane), swept
// along the motion between cutter locations, leaves the machined surface; the residual is
// machined minus design along the normal (docs/verify.md).
//
// The machined heights live on a polar grid (radii × angle columns). Each segment between
// two cutter locations passes every column whose angle it spans (once per revolution on
// a spiral); there the programmed axes X, Z, B are interpolated as the controller does
// (linearly in θ, or by cubic Hermite with each block's velocity from its neighbours, the
// PVT controller's own), the nose centre found from them (on a B machine with a pivot it
// swings on an arc about the pivot), and the nose's lower arc lowers the cells it covers:
// z_m = min(z_m, c_z − √(R² − (ρ − c_r)²)).
// Only the part of the arc within `band` of the contact point is swept: the rest of the
// edge is cut away again by the neighbouring passes (a gouge there is the tool checks'
// business). Cells on the far side of the axis are reached through the opposite column.
//
// Parallel and deterministic: a column and its opposite belong to one thread, which
// applies the segments in path order, so every cell sees the same cuts in the same order
// whatever the thread count; the figures are reduced ring by ring in ring order.

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "freeturn/surface/surface.hpp"
#include "freeturn/path/cutter_points.hpp"
#include "freeturn/tool/compensation.hpp"
#include "freeturn/tool/cutter_location.hpp"

namespace freeturn {

struct SimulationOptions {
  double inner_radius = 0, outer_radius = 0;  // mm, the grid's extent
  double radial_step = 0;  // mm between grid radii
  int columns = 360;       // angles, evenly spaced over the turn (even, so each has an opposite)
  double band = 0;         // mm, half-width of the swept arc about the contact point; 0: R
  // Cells this close to the inner or outer radius are left out of the figures (still in
  // the grid): the spiral's first turn leaves the outermost ring uncut by any pass
  // beyond it, a part of the cut the aperture does not hold.
  double margin = 0;       // mm
  int threads = 0;         // 0: the machine's hardware threads
  Interpolation interpolation = Interpolation::kLinear;  // the controller's, between blocks
  // How the path was compensated: what the programmed axes are (the nose centre, the tip,
  // or the B pivot) and so how the nose centre follows from them.
  CompensationOptions compensation;
  long max_cells = 40'000'000;  // 10 bytes each; a larger grid is refused
};

// Why a place is off the design.
enum class ResidualCause {
  kScallop,  // above the design, mostly the nose's flank between passes
  kChord,    // the interpolated motion between blocks, above or below the design
  kGouge,    // below the design by more than the predicted chord error allows
  kUncut,    // above the design where the nose was held at a crease it cannot reach into
};
const char* to_string(ResidualCause cause);

struct ResidualPlace {
  double r = 0, phi = 0;  // mm, rad
  double residual = 0;    // mm
  ResidualCause cause = ResidualCause::kChord;
  double scallop_part = 0;  // mm: the nose flank's height where it cut (≥ 0)
};

// What the planner predicted for the same region (its contact points within the figures'
// radii): material above the design up to max chord above + the larger of max scallop and
// max uncut residual (where the nose is held at a crease it leaves that much, pass after
// pass), cuts below it up to max chord below; PV the two together.
struct ResidualPrediction {
  double max_scallop = 0, max_chord_above = 0, max_chord_below = 0, max_uncut = 0;  // mm
  double max() const { return max_chord_above + std::max(max_scallop, max_uncut); }
  double min() const { return -max_chord_below; }
  double pv() const { return max() - min(); }
};

// How the planner's predicted PV compares with the simulated one (ratio = predicted /
// simulated): "an upper bound within 10%", "an upper bound, loose by more than 10%", or
// "not an upper bound". A ratio that shows as 1.000 is a bound: the grid's own sampling
// moves the simulated PV by more than that.
const char* prediction_bound_text(double ratio);

struct SimulationResult {
  int rings = 0, columns = 0;
  double radial_step = 0;
  // Residual along the normal (mm), rings × columns (ring-major); NaN where never cut.
  std::vector<double> residual;
  double pv = 0, rms = 0, max = 0, min = 0;
  long uncut = 0;  // cells no pass reached
  double max_r = 0, max_phi = 0, min_r = 0, min_phi = 0;  // where the extremes are
  // The worst places, largest |residual| first, at most five, each the worst of its own
  // stretch of radius (a twentieth of the aperture).
  std::vector<ResidualPlace> worst;
  ResidualPrediction predicted;
};

class CutSimulator final : public CutterSink {
 public:
  // nose_radius: the radius the tool really has (a wrong compensation shows as the
  // difference from the one the path was planned with); its measured waviness δ(ψ − B) is
  // options.compensation.tool's. Throws InputError for a bad grid or one over max_cells.
  CutSimulator(const Surface& design, double nose_radius, const SimulationOptions& options);

  void write(std::span<const CutterLocation> chunk) override;
  // Sweeps what is left, then the residual and its figures over the cells that were cut.
  // Once: the grid becomes the residual.
  SimulationResult finish();

 private:
  void sweep_batch(bool last);
  void sweep_columns(std::size_t end, int pair_begin, int pair_end);
  // held: the segment's nose is held at a crease (its cells are marked uncut residual).
  // b: the tool's rotation (rad), where the waviness is read on the edge.
  void lower_column(int column, double c_r, double c_z, double b, double p_r, bool held);
  // The sweep where the edge sits h above the spindle line, in its rake plane.
  void sweep_rake_plane(std::size_t end, int pair_begin, int pair_end);
  // The lower arc's height at offset d from the nose centre (|d| ≤ R), with the waviness.
  double edge_height(double d, double c_z, double b) const;
  // Lowers cell idx to `height` if that is lower, recording the cut's distance from its
  // contact (mm) and whether its nose was held.
  void lower_cell(std::size_t idx, double height, double from_contact, bool held);

  const Surface& design_;
  double R_;
  SimulationOptions o_;
  int rings_ = 0, threads_ = 1;
  std::vector<double> machined_;       // rings × columns
  // |ρ − contact| of the cut that set the cell in band/32767 (low 15 bits), and whether that
  // cut's nose was held at a crease (kHeldBit).
  std::vector<std::uint16_t> offset_;
  // The batch: locations from pending_[first_] on start segments still to sweep; the one
  // before (if any) gives the first block's velocity in PVT.
  std::vector<CutterLocation> pending_;
  std::size_t first_ = 0;
  ResidualPrediction predicted_;
};

}  // namespace freeturn
