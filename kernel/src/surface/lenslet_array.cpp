#include "freeturn/surface/lenslet_array.hpp"

#include "freeturn/surface/crease_sink.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"

namespace freeturn {
namespace {

// Sag of a sphere of curvature c at lateral distance a from its vertex.
double sphere_sag(double c, double a) {
  return c * a * a / (1 + std::sqrt(1 - c * c * a * a));
}

std::string mm(double v) {
  return significant_text(v, 6) + " mm";
}

// The squared distance in (x, y) from p to the segment from a to b (compared with a
// squared bound: std::hypot's care for overflow costs more than the rest of a query).
double segment_distance_squared(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0.0;
  const double ex = px - ax - t * dx, ey = py - ay - t * dy;
  return ex * ex + ey * ey;
}

// This thread's crease candidates (LensletArray::section_creases): every lenslet whose
// footprint comes within `pad` of a stretch of a radial line, ascending. A later stretch
// whose ends both lie within `pad` of that one lies wholly within it (the pad's
// neighbourhood of a segment is convex), so every footprint that reaches the later one is
// listed: consecutive queries of a path reuse the list instead of scanning grid cells.
struct CreaseCandidates {
  std::uint64_t owner = 0;  // the array's instance id; 0: none yet
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0, pad = 0;
  std::vector<int> lenslets;
};
thread_local CreaseCandidates crease_candidates;

// This thread's candidates for creases_near: every lenslet whose rim can come within
// `radius` of (x, y). A later query whose disc lies inside that one is answered from it.
struct NearbyCandidates {
  std::uint64_t owner = 0;  // the array's instance id; 0: none yet
  double x = 0, y = 0, radius = -1;
  std::vector<int> lenslets;
};
thread_local NearbyCandidates nearby_candidates;

}  // namespace

LensletArray::LensletArray(const LensletArrayOptions& options) : o_(options) {
  const double d = o_.lens_diameter, r = o_.lens_radius, cb = o_.base_curvature;
  if (!(d > 0)) throw InputError("lens_diameter", "must be greater than 0");
  if (!(o_.pitch > 0)) throw InputError("pitch", "must be greater than 0");
  if (d > o_.pitch)
    throw InputError("lens_diameter", "a lenslet of diameter " + mm(d) +
                                          " is larger than its pitch " + mm(o_.pitch) +
                                          ": neighbours would overlap");
  if (!(std::abs(r) >= d / 2))
    throw InputError("lens_radius", "|lens_radius| " + mm(std::abs(r)) +
                                        " is smaller than half the lens diameter " + mm(d / 2));
  // At |R| = D/2 the lenslet is a hemisphere: its wall stands vertical at the rim, its
  // slope infinite there, which no nose follows and no evaluation of the rim can carry (a
  // hemispherical bowl's program was written 6.9 µm into its wall, the checks blind to
  // it). Any radius a rounding larger is a finite wall and is planned.
  if (!(std::isfinite(d / 2 / std::sqrt(r * r - d * d / 4))))
    throw InputError("lens_radius", "|lens_radius| " + mm(std::abs(r)) +
                                        " equals half the lens diameter: each lenslet would be a "
                                        "hemisphere, its wall vertical at its rim (an infinite "
                                        "slope); give a lens radius above " + mm(d / 2));
  if (!(o_.extent > 0)) throw InputError("extent", "must be greater than 0");
  if (std::abs(cb) * o_.extent >= 1)
    throw InputError("base_radius", "the base sphere (radius " + mm(1 / std::abs(cb)) +
                                        ") does not cover the aperture radius " + mm(o_.extent));
  // The rim is where lens and base meet: h = base sag − lens sag at D/2 (both coaxial).
  vertex_height_ = sphere_sag(cb, d / 2) - sphere_sag(1 / r, d / 2);

  // The lookup grid below has (2·extent/pitch + 1)² cells and about π(extent/pitch)²
  // lenslets: bounded before anything is allocated (a pitch typo in µm instead of mm would
  // ask for billions, and a million lenslets take seconds to place; the largest real
  // arrays, 100 mm across at 0.15 mm pitch, stay inside).
  const double side = 2 * o_.extent / o_.pitch + 1;
  if (!(side * side <= 5e5))
    throw InputError("pitch", "a pitch of " + mm(o_.pitch) + " over the aperture radius " + mm(o_.extent) +
                                  " asks for about " + std::to_string(static_cast<long long>(
                                      std::min(1e15, std::numbers::pi * (o_.extent / o_.pitch) * (o_.extent / o_.pitch)))) +
                                  " lenslets, over the 400 000 freeturn places (a 500 000-cell lookup grid); "
                                  "give a larger pitch");
  // Centres, keeping lenslets whose footprint lies inside the extent.
  const double reach = o_.extent - d / 2;
  const auto inside = [&](double x, double y) { return std::hypot(x, y) <= reach + 1e-12; };
  if (o_.pattern == LensletArrayOptions::Pattern::kRings) {
    // Rings at arc spacing `pitch` along the base; each ring holds as many lenslets as fit
    // at arc spacing ≥ pitch (so neighbours never come closer than the pitch).
    const double rb = cb != 0 ? 1 / std::abs(cb) : INFINITY;
    for (int k = 0;; ++k) {
      const double arc = k * o_.pitch;
      const double rho = std::isinf(rb) ? arc : rb * std::sin(arc / rb);
      if (rho > reach + 1e-12 || (!std::isinf(rb) && arc / rb >= std::numbers::pi / 2)) break;
      const int count =
          k == 0 ? 1 : static_cast<int>(std::floor(2 * std::numbers::pi * rho / o_.pitch));
      for (int j = 0; j < count; ++j) {
        const double phi = 2 * std::numbers::pi * j / count;
        add_lenslet(rho * std::cos(phi), rho * std::sin(phi));
      }
    }
  } else {
    const bool hex = o_.pattern == LensletArrayOptions::Pattern::kHexagonal;
    const double dy = hex ? o_.pitch * std::sqrt(3.0) / 2 : o_.pitch;
    const int n = static_cast<int>(std::ceil(o_.extent / dy)) + 1;
    for (int row = -n; row <= n; ++row)
      for (int col = -n; col <= n; ++col) {
        const double x = (col + (hex && (row % 2 != 0) ? 0.5 : 0.0)) * o_.pitch, y = row * dy;
        if (inside(x, y)) add_lenslet(x, y);
      }
  }
  if (lenslets_.empty())
    throw InputError("pitch", "no lenslet of diameter " + mm(d) +
                                  " fits inside the aperture radius " + mm(o_.extent));

  // Lookup grid: each lenslet is listed in every cell its footprint's bounding square meets.
  cell_ = o_.pitch;
  inverse_cell_ = 1 / cell_;
  cells_per_side_ = static_cast<int>(std::ceil(2 * o_.extent / cell_)) + 1;
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(cells_per_side_) * cells_per_side_);
  const auto cell_of = [&](double v) {
    return std::clamp(static_cast<int>(std::floor((v + o_.extent) / cell_)), 0,
                      cells_per_side_ - 1);
  };
  for (int i = 0; i < lenslet_count(); ++i) {
    const Eigen::Vector3d& c = lenslets_[i].base_point;
    const double half = 0.5 * d * 1.001;
    for (int a = cell_of(c.x() - half); a <= cell_of(c.x() + half); ++a)
      for (int b = cell_of(c.y() - half); b <= cell_of(c.y() + half); ++b)
        cells[static_cast<std::size_t>(b) * cells_per_side_ + a].push_back(i);
  }
  // On a sphere the rim is a circle of radius D/2 about the axis, centred R_b cos α along
  // it from the sphere's centre: in (x, y) an ellipse of semi-axes at most D/2 about
  // cos α · c_xy, which lies |c_xy|(1 − cos α) from the base point's c_xy.
  crease_reach_ = 0.5 * d + (cb != 0 ? o_.extent * (1 - std::sqrt(std::max(0.0, 1 - 0.25 * d * d * cb * cb)))
                                     : 0.0);
  crease_reach_ += 1e-9 * (1 + o_.extent);
  // A lenslet's height is z = C_z − σ√(r² − d²), d the distance in (x, y) from its
  // sphere's centre, σ the sign of r: a dome (σ < 0) has a negative definite Hessian; a
  // bowl's largest eigenvalue is 1/w + d²/w³ = r²/w³ (w = √(r² − d²)), largest where its
  // footprint reaches farthest from the centre: at most crease_reach_ beyond the base point.
  for (const Lenslet& l : lenslets_) {
    if (!(o_.lens_radius > 0)) break;
    const double d_far = std::hypot(l.centre.x() - l.base_point.x(), l.centre.y() - l.base_point.y()) + crease_reach_;
    const double w2 = r * r - d_far * d_far;
    lenslet_bend_ = w2 > 0 ? std::max(lenslet_bend_, r * r / (w2 * std::sqrt(w2)))
                           : std::numeric_limits<double>::infinity();
  }
  // What section_creases needs of each lenslet on a sphere, computed once.
  if (cb != 0) {
    const double rb = 1 / std::abs(cb);
    rim_cosine_ = std::sqrt(std::max(0.0, rb * rb - 0.25 * d * d));
    for (const Lenslet& l : lenslets_) {
      const Eigen::Vector3d& c = l.base_point;
      rim_height_.push_back(std::sqrt(std::max(0.0, rb * rb - (c.x() * c.x() + c.y() * c.y()))));
    }
  }
  // creases_near's bounds. At a rim the lens's and the base's normals lie in one plane with
  // the lenslet's axis, at α_L = asin(D/2|r|) and α_B = asin(D/2 R_b) from it, so at most
  // β = α_L + α_B apart. The slope's jump along a unit direction t in (x, y) is
  // (∇z_L − ∇z_B)·t, and with ∇z = −n_xy/n_z, |∇z_L − ∇z_B| = |n_L,xy n_B,z − n_B,xy n_L,z|
  // / (n_L,z n_B,z) ≤ |n_L × n_B| / (n_L,z n_B,z) = sin β / (n_L,z n_B,z). The axis leans
  // at most τ = asin(|c_xy|/R_b) from +z, so n_L,z ≥ cos(τ + α_L), n_B,z ≥ cos(τ + α_B).
  {
    double farthest = 0;
    for (const Lenslet& l : lenslets_)
      farthest = std::max(farthest, std::hypot(l.base_point.x(), l.base_point.y()));
    const double lean = cb != 0 ? std::asin(std::min(1.0, farthest * std::abs(cb))) : 0.0;
    const double alpha_l = std::asin(std::min(1.0, 0.5 * d / std::abs(r)));
    const double alpha_b = cb != 0 ? std::asin(std::min(1.0, 0.5 * d * std::abs(cb))) : 0.0;
    const double right = 0.5 * std::numbers::pi;
    crease_jump_ = lean + std::max(alpha_l, alpha_b) < right
                       ? std::sin(std::min(alpha_l + alpha_b, right)) /
                             (std::cos(lean + alpha_l) * std::cos(lean + alpha_b))
                       : std::numeric_limits<double>::infinity();
    rim_reach_ = farthest + crease_reach_;
  }
  // creases_near's rim shapes. The rim is a circle of radius D/2 about the lenslet's axis
  // a, in the plane normal to it, centred cos α · c_xy in (x, y) (on a plane, c_xy): seen
  // along z, an ellipse of semi-axes D/2 and (D/2)·a_z. An ellipse's normal at a point
  // leans from the direction from its centre by at most atan((p² − q²)/(2pq)) (semi-axes
  // p ≥ q), and it bends at most p/q².
  {
    const double cos_alpha = cb != 0 ? rim_cosine_ * std::abs(cb) : 1.0, half = 0.5 * d;
    for (const Lenslet& l : lenslets_) {
      const double a_z = cb != 0 ? std::abs(l.axis.z()) : 1.0;
      rim_shape_.push_back({cos_alpha * l.base_point.x(), cos_alpha * l.base_point.y(),
                            std::atan((1 - a_z * a_z) / (2 * a_z)), 1 / (half * a_z * a_z)});
    }
  }
  // The footprint test's constants (lenslet_at).
  const double sign = cb > 0 ? 1.0 : -1.0;
  if (cb != 0) rb_squared_ = 1 / (cb * cb);
  half_squared_ = 0.25 * o_.lens_diameter * o_.lens_diameter;
  lookup_reach_ = o_.extent + cell_;
  for (int i = 0; i < lenslet_count(); ++i) {
    const Lenslet& l = lenslets_[static_cast<std::size_t>(i)];
    by_lenslet_.push_back({l.base_point.x(), l.base_point.y(), sign * l.axis.x(),
                           sign * l.axis.y(), l.axis.z() * l.axis.z(), i});
  }
  lookup_count_ = static_cast<int>(by_lenslet_.size());
  // Footprints overlap only if two lenslets listed in one cell do (a point in both lies
  // in a cell both are listed in). On a sphere the footprint is the cap within α of the
  // lenslet's axis (R_b sin α = D/2), and two caps are apart when their axes are at least
  // 2α apart; on a plane, discs whose centres are at least D apart. A margin of 1e-9
  // keeps a point within rounding of both rims out of both.
  disjoint_ = true;
  const double alpha = cb != 0 ? std::asin(0.5 * d * std::abs(cb)) : 0.0;
  for (const auto& list : cells)
    for (std::size_t p = 0; p < list.size() && disjoint_; ++p)
      for (std::size_t q = p + 1; q < list.size() && disjoint_; ++q) {
        const Lenslet& i = lenslets_[static_cast<std::size_t>(list[p])];
        const Lenslet& j = lenslets_[static_cast<std::size_t>(list[q])];
        disjoint_ = cb != 0 ? 2 * std::asin(0.5 * (i.axis - j.axis).norm()) >= 2 * alpha * (1 + 1e-9)
                            : (i.base_point - j.base_point).norm() >= d * (1 + 1e-9);
      }
  cell_start_.push_back(0);
  for (const auto& list : cells) {
    cell_items_.insert(cell_items_.end(), list.begin(), list.end());
    cell_start_.push_back(static_cast<int>(cell_items_.size()));
  }
  // lenslet_at's own grid, up to four times finer (at most about two million cells), each
  // cell listing only the lenslets whose footprint can reach it (within crease_reach_ of
  // the base point): a point on the base between lenslets, near half of a path's
  // queries, then tests one or two footprints, or none, instead of a pitch-sized cell's
  // three or four. In ascending lenslet order, like the cells above, so that where
  // footprints overlap the first to hold a point is the same lenslet.
  const int fine = std::clamp(static_cast<int>(std::sqrt(2e6 / (side * side))), 1, 4);
  fine_cell_ = cell_ / fine;
  inverse_fine_cell_ = 1 / fine_cell_;
  fine_per_side_ = cells_per_side_ * fine;
  std::vector<int> fine_count(static_cast<std::size_t>(fine_per_side_) * fine_per_side_ + 1, 0);
  const auto fine_cells_of = [&](const Lenslet& l, auto&& visit) {
    const double px = l.base_point.x(), py = l.base_point.y();
    const auto index = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v + o_.extent) * inverse_fine_cell_)), 0,
                        fine_per_side_ - 1);
    };
    for (int b = index(py - crease_reach_); b <= index(py + crease_reach_); ++b)
      for (int a = index(px - crease_reach_); a <= index(px + crease_reach_); ++a) {
        // The distance from the base point to the cell's square (the edge cells extend to
        // infinity: the clamp sends points beyond the grid there).
        const double x_lo = a == 0 ? -1e300 : -o_.extent + a * fine_cell_;
        const double x_hi = a == fine_per_side_ - 1 ? 1e300 : -o_.extent + (a + 1) * fine_cell_;
        const double y_lo = b == 0 ? -1e300 : -o_.extent + b * fine_cell_;
        const double y_hi = b == fine_per_side_ - 1 ? 1e300 : -o_.extent + (b + 1) * fine_cell_;
        const double dx = std::max({x_lo - px, 0.0, px - x_hi});
        const double dy = std::max({y_lo - py, 0.0, py - y_hi});
        if (dx * dx + dy * dy <= crease_reach_ * crease_reach_)
          visit(static_cast<std::size_t>(b) * fine_per_side_ + a);
      }
  };
  for (const Lenslet& l : lenslets_) fine_cells_of(l, [&](std::size_t k) { ++fine_count[k + 1]; });
  for (std::size_t k = 1; k < fine_count.size(); ++k) fine_count[k] += fine_count[k - 1];
  fine_start_ = fine_count;
  fine_lookup_.resize(static_cast<std::size_t>(fine_start_.back()));
  for (int i = 0; i < lenslet_count(); ++i)  // ascending: each cell's list is in lenslet order
    fine_cells_of(lenslets_[static_cast<std::size_t>(i)], [&](std::size_t k) {
      fine_lookup_[static_cast<std::size_t>(fine_count[k]++)] = by_lenslet_[static_cast<std::size_t>(i)];
    });
}

void LensletArray::add_lenslet(double x, double y) {
  const double cb = o_.base_curvature;
  Lenslet l;
  l.base_point = {x, y, sphere_sag(cb, std::hypot(x, y))};
  // The base normal toward +z: for a sphere, along (centre − point) when c > 0.
  const double s = std::sqrt(1 - cb * cb * (x * x + y * y));
  l.axis = Eigen::Vector3d(-cb * x, -cb * y, s).normalized();
  l.vertex = l.base_point + vertex_height_ * l.axis;
  l.centre = l.vertex + o_.lens_radius * l.axis;
  lenslets_.push_back(l);
}

const char* LensletArray::type() const {
  return o_.base_curvature != 0 ? "compound_eye" : "microlens_array";
}

double LensletArray::max_bend(double radius) const {
  // The base z = (1 − q)/c, q = √(1 − c²s): its Hessian cI/q + c³ppᵀ/q³ has the
  // eigenvalues c/q (along the circle) and c/q³ (along the radius), largest at the
  // largest s; both ≤ 0 on a convex base.
  const double c = o_.base_curvature, s = radius * radius;
  double base = 0;
  if (c > 0) {
    const double q2 = 1 - c * c * s;
    base = q2 > 0 ? c / (q2 * std::sqrt(q2)) : std::numeric_limits<double>::infinity();
  }
  if (!(radius >= 0)) base = std::numeric_limits<double>::infinity();
  return std::max(base, lenslet_bend_);
}

double LensletArray::defined_radius() const {
  return o_.base_curvature != 0 ? 1 / std::abs(o_.base_curvature) : Surface::defined_radius();
}

int LensletArray::lenslet_at(double x, double y) const {
  // Written so that NaN coordinates (a point off a transformed surface) find no lenslet.
  if (!(std::abs(x) <= lookup_reach_) || !(std::abs(y) <= lookup_reach_)) return -1;
  // The lenslet this thread found last: a path's consecutive queries mostly stay in one.
  // Where no two footprints overlap (disjoint_), the lenslet that holds the point is the
  // only one, so trying it first changes no answer; any array's index is only a guess,
  // checked against this one's own data. Read at a fixed offset from the thread pointer
  // (the library's TLS model, kernel/CMakeLists.txt), not through __tls_get_addr, whose
  // call was about a twentieth of a compound eye's planning (this is asked for every
  // evaluation of the design).
  static thread_local int last_found = -1;
  // That lenslet, then the fine grid's cell's in order (x + extent ≥ −cell here:
  // truncation and floor differ only on (−1, 0), clamped to 0). The footprint test is
  // chosen once a query, outside the loop: a plane's or a sphere's.
  const auto first_holding = [&](const auto& holds) {
    if (disjoint_ && last_found >= 0 && last_found < lookup_count_ &&
        holds(by_lenslet_[static_cast<std::size_t>(last_found)]))
      return last_found;
    const int a =
        std::clamp(static_cast<int>((x + o_.extent) * inverse_fine_cell_), 0, fine_per_side_ - 1);
    const int b =
        std::clamp(static_cast<int>((y + o_.extent) * inverse_fine_cell_), 0, fine_per_side_ - 1);
    const int k = b * fine_per_side_ + a;
    for (int idx = fine_start_[k]; idx < fine_start_[k + 1]; ++idx) {
      const LookupEntry& l = fine_lookup_[static_cast<std::size_t>(idx)];
      if (holds(l)) return last_found = l.lenslet;
    }
    return -1;
  };
  if (o_.base_curvature == 0)
    return first_holding([&](const LookupEntry& l) {
      const double wx = x - l.px, wy = y - l.py;
      return wx * wx + wy * wy < half_squared_;
    });
  // On a sphere of radius R_b about O the point p of the base (over (x, y)) lies in
  // lenslet i's footprint when the angle at O between p and the base point c_i is below α
  // (R_b sin α = D/2). With p − O = (x, y, −sgn(c)·S), S = √(R_b² − s), and
  // c_i − O = −sgn(c)·R_b·a_i, that is a_z·S > R_b cos α + sgn(c)(a_x x + a_y y) = M,
  // tested squared as a_z²(R_b² − s) > M² where M > 0: no square root (the planner asks
  // this for every evaluation of the design, and the root's latency was most of it).
  // Past the sphere's rim (S² < 0) no footprint reaches.
  const double depth_squared = rb_squared_ - (x * x + y * y);  // S²
  if (!(depth_squared >= 0)) return -1;
  return first_holding([&](const LookupEntry& l) {
    const double m = rim_cosine_ + l.ux * x + l.uy * y;
    return m <= 0 || l.w2 * depth_squared > m * m;
  });
}

int LensletArray::section_creases(const RadialLine& line, double rho_lo, double rho_hi,
                                  std::span<double> out) const {
  return LensletArray::line_creases(0.0, 0.0, line, rho_lo, rho_hi, out);
}

int LensletArray::line_creases(double ox, double oy, const RadialLine& line, double rho_lo,
                               double rho_hi, std::span<double> out) const {
  const double half = 0.5 * o_.lens_diameter, cb = o_.base_curvature;
  if (cb != 0 && (ox != 0 || oy != 0)) return -1;
  if (!(rho_lo <= rho_hi) || !std::isfinite(rho_lo) || !std::isfinite(rho_hi)) return 0;
  if (!std::isfinite(ox) || !std::isfinite(oy)) return -1;
  const double ct = line.cos, st = line.sin;
  const double x0 = ox + rho_lo * ct, x1 = ox + rho_hi * ct, y0 = oy + rho_lo * st,
               y1 = oy + rho_hi * st;
  CreaseCandidates& c = crease_candidates;
  const double pad_squared = c.pad * c.pad;
  if (c.owner != id_.value ||
      !(segment_distance_squared(x0, y0, c.x0, c.y0, c.x1, c.y1) <= pad_squared &&
        segment_distance_squared(x1, y1, c.x0, c.y0, c.x1, c.y1) <= pad_squared)) {
    // The lenslets listed in the cells the padded stretch's bounding box meets (a
    // footprint lies within its bounding square, which is what the cells list), kept
    // where the footprint can come within the pad of the stretch.
    c.owner = id_.value;
    c.x0 = x0, c.y0 = y0, c.x1 = x1, c.y1 = y1;
    c.pad = 0.25 * o_.pitch;
    c.lenslets.clear();
    const auto cell_of = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v + o_.extent) / cell_)), 0,
                        cells_per_side_ - 1);
    };
    const double keep_squared = (crease_reach_ + c.pad) * (crease_reach_ + c.pad);
    const int a_lo = cell_of(std::min(x0, x1) - c.pad), a_hi = cell_of(std::max(x0, x1) + c.pad);
    const int b_lo = cell_of(std::min(y0, y1) - c.pad), b_hi = cell_of(std::max(y0, y1) + c.pad);
    for (int b = b_lo; b <= b_hi; ++b)
      for (int a = a_lo; a <= a_hi; ++a) {
        const int k = b * cells_per_side_ + a;
        for (int idx = cell_start_[k]; idx < cell_start_[k + 1]; ++idx) {
          const int i = cell_items_[static_cast<std::size_t>(idx)];
          const LookupEntry& l = by_lenslet_[static_cast<std::size_t>(i)];
          if (segment_distance_squared(l.px, l.py, x0, y0, x1, y1) <= keep_squared)
            c.lenslets.push_back(i);
        }
      }
    std::sort(c.lenslets.begin(), c.lenslets.end());
    c.lenslets.erase(std::unique(c.lenslets.begin(), c.lenslets.end()), c.lenslets.end());
  }
  CreaseSink found(out, rho_lo, rho_hi);
  for (const int i : c.lenslets) {
    const LookupEntry& l = by_lenslet_[static_cast<std::size_t>(i)];
    // The base point from the line's origin (the axis but for a decentred array).
    const double cx = l.px - ox, cy = l.py - oy;
    const double along = cx * ct + cy * st;  // the centre's projection on the line
    // A footprint lies within crease_reach_ of its centre in (x, y): a lenslet farther
    // from the line, or beside the stretch, has no rim on it there. Most candidates end
    // here, before the roots below.
    if (!(std::abs(cy * ct - cx * st) <= crease_reach_ && along >= rho_lo - crease_reach_ &&
          along <= rho_hi + crease_reach_))
      continue;
    if (cb == 0) {
      // |ρ e_r − c|² = (D/2)²: ρ² − 2ρ·along + |c|² − (D/2)² = 0.
      const double disc = along * along - (cx * cx + cy * cy) + half * half;
      if (disc < 0) continue;
      found.add(along - std::sqrt(disc));
      found.add(along + std::sqrt(disc));
      continue;
    }
    // On the sphere (centre O on the axis, radius R_b) the rim is where the angle at O
    // between the point and c is α, sin α = (D/2)/R_b: with ρ = R_b sin φ,
    //   along·sin φ + √(R_b² − |c_xy|²)·cos φ = R_b cos α.
    const double rb = 1 / std::abs(cb);
    const double bc = rim_height_[static_cast<std::size_t>(l.lenslet)];
    const double m = std::sqrt(along * along + bc * bc);  // mm-sized: no overflow
    const double q = rim_cosine_ / m;
    if (!(q <= 1)) continue;
    // φ + β = asin q or π − asin q, with cos β = along/m, sin β = bc/m, kept where
    // |φ| ≤ π/2 (cos φ ≥ 0): sin φ and cos φ by the angle-sum rules, no inverse
    // trigonometric function (three of them per lenslet were a tenth of the planner).
    const double cos_beta = along / m, sin_beta = bc / m;
    const double root = std::sqrt(std::max(0.0, 1 - q * q));  // cos(asin q)
    if (root * cos_beta + q * sin_beta >= 0) found.add(rb * (q * cos_beta - root * sin_beta));
    if (q * sin_beta - root * cos_beta >= 0) found.add(rb * (q * cos_beta + root * sin_beta));
  }
  return found.finish();
}

bool LensletArray::crease_circles(std::vector<CreaseCircle>& out) const {
  const double cb = o_.base_curvature, half = 0.5 * o_.lens_diameter;
  // The base point lies 1/c along −axis from the base's centre; the rim, cos α of that.
  const double lift =
      cb != 0 ? (1 - std::sqrt(std::max(0.0, 1 - half * half * cb * cb))) / cb : 0.0;
  out.reserve(out.size() + lenslets_.size());
  for (const Lenslet& l : lenslets_) out.push_back({l.base_point + lift * l.axis, l.axis, half});
  return true;
}

int LensletArray::creases_near(double x, double y, double radius,
                               std::span<NearbyCrease> out) const {
  if (!disjoint_ || !std::isfinite(crease_jump_)) return -1;
  if (!(radius >= 0) || !std::isfinite(radius) || !std::isfinite(x) || !std::isfinite(y)) return -1;
  const double cb = o_.base_curvature, s = x * x + y * y;
  // On a sphere: the base's slope is at most ρ_m/√(R_b² − ρ_m²) on the stretch in (x, y)
  // from the point to any rim (both within ρ_m of the axis).
  double to_plane = 1, depth = 0;  // 1/√(1 + slope²); S = √(R_b² − s)
  if (cb != 0) {
    const double rho_m = std::max(std::sqrt(s), rim_reach_);
    const double q = rb_squared_ - rho_m * rho_m;
    if (!(q > 0)) return -1;
    to_plane = std::sqrt(q / rb_squared_);  // 1/√(1 + ρ_m²/q)
    depth = std::sqrt(rb_squared_ - s);
  }
  NearbyCandidates& c = nearby_candidates;
  // The list holds every lenslet near the disc it was made for, so it serves any disc
  // inside that one (compared squared: the C library's hypot here was called 2.95 million
  // times on the chord job cut to 2 mm).
  const double room = c.radius - radius, dx = x - c.x, dy = y - c.y;
  if (c.owner != id_.value || !(room >= 0 && dx * dx + dy * dy <= room * room)) {
    c.owner = id_.value;
    c.x = x, c.y = y;
    c.radius = radius + 0.25 * o_.pitch;
    c.lenslets.clear();
    // A rim lies within crease_reach_ of its base point in (x, y), and a base point lies in
    // the cell that lists its lenslet (its footprint's square holds it).
    const double keep = c.radius + crease_reach_;
    const auto cell_of = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v + o_.extent) / cell_)), 0,
                        cells_per_side_ - 1);
    };
    for (int b = cell_of(y - keep); b <= cell_of(y + keep); ++b)
      for (int a = cell_of(x - keep); a <= cell_of(x + keep); ++a) {
        const int k = b * cells_per_side_ + a;
        for (int idx = cell_start_[k]; idx < cell_start_[k + 1]; ++idx) {
          const int i = cell_items_[static_cast<std::size_t>(idx)];
          const LookupEntry& l = by_lenslet_[static_cast<std::size_t>(i)];
          if ((l.px - x) * (l.px - x) + (l.py - y) * (l.py - y) <= keep * keep)
            c.lenslets.push_back(i);
        }
      }
    std::sort(c.lenslets.begin(), c.lenslets.end());
    c.lenslets.erase(std::unique(c.lenslets.begin(), c.lenslets.end()), c.lenslets.end());
  }
  const double half = 0.5 * o_.lens_diameter;
  const double rb = cb != 0 ? 1 / std::abs(cb) : 0.0;
  const double cos_alpha = cb != 0 ? rim_cosine_ / rb : 1.0, sin_alpha = half * std::abs(cb);
  int count = 0;
  for (const int i : c.lenslets) {
    const LookupEntry& l = by_lenslet_[static_cast<std::size_t>(i)];
    double distance;
    bool inside;
    if (cb == 0) {
      const double from_centre = std::sqrt((x - l.px) * (x - l.px) + (y - l.py) * (y - l.py));
      distance = std::abs(from_centre - half);
      inside = from_centre < half;
    } else {
      // φ, the angle at the sphere's centre between the point's base point and the axis:
      // R_b cos φ = a_z S − sgn(c)(a_x x + a_y y) (lenslet_at). The rim is φ = α; along the
      // sphere a rim point is at least R_b|φ − α| away, so at least 2R_b sin(|φ − α|/2) ≥
      // R_b|sin(φ − α)| in space, and at least that times 1/√(1 + slope²) in (x, y).
      const double cos_phi =
          std::clamp((std::sqrt(l.w2) * depth - (l.ux * x + l.uy * y)) / rb, -1.0, 1.0);
      const double sin_phi = std::sqrt(1 - cos_phi * cos_phi);
      distance = rb * std::abs(sin_phi * cos_alpha - cos_phi * sin_alpha) * to_plane;
      inside = cos_phi > cos_alpha;
    }
    if (!(distance <= radius)) continue;
    if (count == static_cast<int>(out.size())) return -1;
    // A footprint is convex in (x, y) (a disc, or a spherical cap's projection): a
    // half-line from inside leaves it once, one from outside crosses its rim twice at most.
    NearbyCrease& crease = out[static_cast<std::size_t>(count++)];
    crease = {distance, crease_jump_, inside ? 1 : 2};
    // How the rim lies (rim_shape_; the slope's jump is along its normal: z_L − z_B is 0
    // along the rim).
    const RimShape& rim = rim_shape_[static_cast<std::size_t>(l.lenslet)];
    const double from_x = x - rim.centre_x, from_y = y - rim.centre_y;
    const double from = std::sqrt(from_x * from_x + from_y * from_y);  // mm: no overflow
    if (from > 0 && std::isfinite(rim.curvature)) {
      crease.normal_x = from_x / from;
      crease.normal_y = from_y / from;
      crease.centre_distance = from;
      crease.normal_slack = rim.normal_slack;
      crease.curvature = rim.curvature;
    }
  }
  return count;
}

// The spheres' values and gradients in closed form (height_derivatives below adds the
// Hessians): the planner's every evaluation of the design comes here, and Jet<1>'s general
// arithmetic cost a third more.
void LensletArray::sag_gradient(double x, double y, double& z, double& zx, double& zy) const {
  const int i = lenslet_at(x, y);
  if (i < 0) {
    // z = c s/(1 + √(1 − c²s)), ∇z = c (x, y)/√(1 − c²s).
    const double c = o_.base_curvature, s = x * x + y * y;
    const double q = std::sqrt(1 - c * c * s);
    z = c * s / (1 + q);
    const double g = c / q;
    zx = g * x;
    zy = g * y;
    return;
  }
  // z = C_z − sgn(R) √(R² − dx² − dy²), ∇z = sgn(R) (dx, dy)/√(…).
  const Eigen::Vector3d& centre = lenslets_[static_cast<std::size_t>(i)].centre;
  const double r = o_.lens_radius, dx = x - centre.x(), dy = y - centre.y();
  const double q = std::sqrt(r * r - dx * dx - dy * dy);
  const double sign = r > 0 ? 1.0 : -1.0;
  z = centre.z() - sign * q;
  const double g = sign / q;
  zx = g * dx;
  zy = g * dy;
}

// The same spheres with their Hessians: the chain rule through the square roots written
// out, operation for operation and in the same order as the Jet<2> formulas they replace
// (z = C_z − sgn(R)·√(R² − (x − C_x)² − (y − C_y)²) on a lenslet, conic_sag on the base),
// so the bits are the jets' (tests/surface/lenslet_array_test.cpp compares them) without
// the jets' products of zero components. A held nose's Newton solve asks this twice a step.
HeightDerivatives LensletArray::height_derivatives(double x, double y) const {
  const int i = lenslet_at(x, y);
  if (i < 0) {
    // c·s/(1 + √(1 − c²s)), s = x² + y²: ∇s = (2x, 2y), ∇²s = 2I.
    const double c = o_.base_curvature, cc = c * c;
    const double r2 = x * x + y * y, r2x = x + x, r2y = y + y;
    // w = 1 − c²s and q = √w.
    const double w = 1.0 - cc * r2, wx = -(cc * r2x), wy = -(cc * r2y), wxx = -(cc * 2.0);
    const double q = std::sqrt(w), f1 = 0.5 / q, f2 = -0.25 / (q * w);
    const double qx = f1 * wx, qy = f1 * wy;
    const double qxx = f1 * wxx + f2 * wx * wx, qxy = f2 * wx * wy, qyy = f1 * wxx + f2 * wy * wy;
    // 1/(1 + q), the denominator's reciprocal.
    const double v = 1.0 / (q + 1.0), g1 = -v * v, g2 = 2 * v * v * v;
    const double vx = g1 * qx, vy = g1 * qy;
    const double vxx = g1 * qxx + g2 * qx * qx, vxy = g1 * qxy + g2 * qx * qy,
                 vyy = g1 * qyy + g2 * qy * qy;
    // The numerator c·s times it.
    const double n = c * r2, nx = c * r2x, ny = c * r2y, nxx = c * 2.0;
    return {n * v,
            nx * v + n * vx,
            ny * v + n * vy,
            nxx * v + 2 * nx * vx + n * vxx,
            nx * vy + ny * vx + n * vxy,
            nxx * v + 2 * ny * vy + n * vyy};
  }
  const Eigen::Vector3d& centre = lenslets_[static_cast<std::size_t>(i)].centre;
  const double r = o_.lens_radius, sign = r > 0 ? 1.0 : -1.0;
  const double ex = x - centre.x(), ey = y - centre.y();
  // u = R² − ex² − ey² (∇u = −2(ex, ey), ∇²u = −2I) and s = √u.
  const double u = r * r - ex * ex - ey * ey, ux = -(ex + ex), uy = -(ey + ey);
  const double s = std::sqrt(u), f1 = 0.5 / s, f2 = -0.25 / (s * u);
  const double sx = f1 * ux, sy = f1 * uy;
  const double sxx = f1 * -2.0 + f2 * ux * ux, sxy = f2 * ux * uy, syy = f1 * -2.0 + f2 * uy * uy;
  return {centre.z() - sign * s, -(sign * sx),  -(sign * sy),
          -(sign * sxx),         -(sign * sxy), -(sign * syy)};
}

}  // namespace freeturn
