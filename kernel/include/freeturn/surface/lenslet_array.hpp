#pragma once
// Spherical lenslets on a spherical base (a compound eye, papers 000 and 002) or on a plane
// (a microlens array).
//
// Lenslet i sits at a centre c_i on the base; its axis is the base normal n_i there, which
// passes through the base sphere's centre, so in the lenslet's own frame the base and the
// lens are coaxial spheres. The lens covers the footprint of diameter D (lateral distance
// from its axis ≤ D/2) and its vertex height is chosen so that it meets the base exactly
// on the footprint's rim: the surface is continuous, with a crease at each rim. Outside
// every footprint the surface is the base.
//
// A point finds its lenslet through a uniform grid over (x, y) whose cells list the
// lenslets that can cover them: a few candidates per query, whatever the lenslet count.

#include <Eigen/Core>
#include <vector>

#include "freeturn/core/instance_id.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct LensletArrayOptions {
  double base_curvature = 0;  // 1/mm; 0 for a microlens array on a plane
  double lens_radius = 0;     // mm, signed (> 0: centre of curvature toward +z), |R| ≥ D/2
  double lens_diameter = 0;   // mm, footprint diameter D, ≤ pitch
  double pitch = 0;           // mm, centre spacing (along the base for a compound eye)
  enum class Pattern { kRings, kHexagonal, kSquare } pattern = Pattern::kHexagonal;
  double extent = 0;  // mm, lenslets whose footprint lies within this radius
};

class LensletArray final : public Surface {
 public:
  // Throws InputError for a lenslet larger than its pitch, a lens radius smaller than half
  // its diameter, a base too curved for the extent, or no lenslet inside the extent.
  explicit LensletArray(const LensletArrayOptions& options);

  const char* type() const override;
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override;
  HeightDerivatives height_derivatives(double x, double y) const override;
  double defined_radius() const override;
  bool has_creases() const override { return true; }
  // A bowl's rim is a ridge; domes meet each other and the base in valleys.
  bool may_have_ridges() const override { return o_.lens_radius > 0; }
  // The base sphere's bend within `radius` and every lenslet's within its footprint.
  double max_bend(double radius) const override;
  // The same bound (no section of a lenslet or of the base bends more than the surface), by
  // a direct call: the nose's searches ask it about 18 times a cutter point.
  double max_section_bend(double radius) const override { return LensletArray::max_bend(radius); }
  // Where the radial line crosses the lenslets' rims, in closed form (a circle on a plane
  // base; on a sphere, a cone about the lenslet's axis through the sphere's centre).
  int section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                      std::span<double> out) const override;
  // Along any line on a plane base (a decentred array's radial sections); on a sphere only
  // through the axis (−1 off it: the rim's closed form there is the radial one).
  int line_creases(double x0, double y0, const RadialLine& line, double rho_lo, double rho_hi,
                   std::span<double> out) const override;
  // Each lenslet's rim within `radius`: its distance from the angle at the base sphere's
  // centre between the point and the lenslet's axis (exact on a plane), the slope's jump
  // from the angle between the lens's and the base's normals there. −1 where footprints
  // overlap (a rim inside another footprint meets two lenses, not a lens and the base).
  int creases_near(double x, double y, double radius, std::span<NearbyCrease> out) const override;
  // Each lenslet's rim: the circle of radius D/2 about its axis where its sphere meets the
  // base (on a sphere of radius R_b, cos α·R_b from the base's centre, sin α = D/(2R_b)).
  bool crease_circles(std::vector<CreaseCircle>& out) const override;

  int lenslet_count() const { return static_cast<int>(lenslets_.size()); }
  // Index of the lenslet whose footprint holds (x, y), or −1 on the base.
  int lenslet_at(double x, double y) const;
  // The lenslet's vertex and axis (unit, toward +z).
  Eigen::Vector3d lenslet_vertex(int i) const { return lenslets_[i].vertex; }
  Eigen::Vector3d lenslet_axis(int i) const { return lenslets_[i].axis; }

 private:
  struct Lenslet {
    Eigen::Vector3d base_point;  // c_i on the base
    Eigen::Vector3d axis;        // n_i
    Eigen::Vector3d vertex;      // c_i + h n_i
    Eigen::Vector3d centre;      // of the lens sphere: vertex + R n_i
  };
  void add_lenslet(double x, double y);

  InstanceId id_;  // the key of each thread's crease candidates (section_creases)
  LensletArrayOptions o_;
  double vertex_height_ = 0;  // h, along the axis
  std::vector<Lenslet> lenslets_;
  // The pitch-sized grid (section_creases' candidates): cells of size cell_ over
  // [−extent, extent]²; cell k lists lenslets cell_items_[cell_start_[k] … cell_start_[k + 1]).
  double cell_ = 0, inverse_cell_ = 0;
  int cells_per_side_ = 0;
  std::vector<int> cell_start_, cell_items_;
  // What lenslet_at and section_creases read of a lenslet.
  struct LookupEntry {
    double px, py;      // the base point's (x, y)
    double ux, uy, w2;  // on a sphere: sgn(c)·a_x, sgn(c)·a_y and a_z² of the axis a
    int lenslet;
  };
  std::vector<LookupEntry> by_lenslet_;  // one per lenslet, in lenslet order
  // lenslet_at's finer grid: cells of fine_cell_, cell k listing the lenslets whose
  // footprint can reach it, fine_lookup_[fine_start_[k] … fine_start_[k + 1]).
  double fine_cell_ = 0, inverse_fine_cell_ = 0;
  int fine_per_side_ = 0;
  std::vector<int> fine_start_;
  std::vector<LookupEntry> fine_lookup_;
  bool disjoint_ = false;                // no two footprints overlap (lenslet_at's hint)
  // On a sphere of radius R_b: √(R_b² − |c_xy|²) per lenslet (its base point's height over
  // the sphere's centre) and R_b cos α = √(R_b² − (D/2)²), for section_creases and
  // lenslet_at.
  std::vector<double> rim_height_;
  double rim_cosine_ = 0;
  // How far from its base point's (x, y) a footprint reaches in (x, y) (section_creases).
  double crease_reach_ = 0;
  // The largest bend of any lenslet's sphere over its footprint (max_bend).
  double lenslet_bend_ = 0;
  double rb_squared_ = 0;  // R_b² on a sphere (lenslet_at)
  // lenslet_at's other constants: (D/2)², how far from the axis in x or y a lookup can
  // find a lenslet (the extent and a cell), and by_lenslet_'s count.
  double half_squared_ = 0, lookup_reach_ = 0;
  int lookup_count_ = 0;
  // creases_near: the slope's largest jump across a rim, and how far from the axis in
  // (x, y) a rim reaches.
  double crease_jump_ = 0;
  double rim_reach_ = 0;
  // creases_near's rim directions, per lenslet: the rim ellipse's centre in (x, y), how far
  // its normal leans from the direction from that centre, and its largest bend.
  struct RimShape {
    double centre_x = 0, centre_y = 0, normal_slack = 0, curvature = 0;
  };
  std::vector<RimShape> rim_shape_;
};

}  // namespace freeturn
