// The nose held at a concave crease (path/section_envelope.hpp): the centre against the
// closed-form intersection of the two flanks' offsets, the uncut residual against its
// closed form, and no point of the nose below the design, checked by brute force.
#include "freeturn/path/section_envelope.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "dense_check.hpp"
#include "fixtures.hpp"
#include "freeturn/path/base_surface_fit.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/path/tight_troughs.hpp"
#include "freeturn/surface/lenslet_array.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/sinusoidal.hpp"
#include "freeturn/surface/zernike.hpp"
#include "freeturn/tool/compensation.hpp"
#include "nose_brute_force.hpp"
#include "nurbs/fixtures.hpp"

namespace freeturn {
namespace {

using test::brute_overlap;
using test::touch_at;

// Two convex spherical domes meeting at the crease line x = x_k: dome A (radius RA, its
// centre e_A before the crease) for x < x_k, dome B (radius RB, e_B beyond it) for x ≥ x_k,
// their heights matched on the radial section θ = 0. In that section the crease is concave
// with an angle δ = atan(e_A/√(RA² − e_A²)) + atan(e_B/√(RB² − e_B²)).
class TwoDomes final : public Surface {
 public:
  static constexpr double kCrease = 2.0, kRA = 5.0, kEA = 0.45, kRB = 3.0, kEB = 0.2;
  static double height_a() { return 0.0; }
  static double height_b() {
    return std::sqrt(kRA * kRA - kEA * kEA) - std::sqrt(kRB * kRB - kEB * kEB);
  }
  const char* type() const override { return "two_domes"; }
  bool has_creases() const override { return true; }
  int section_creases(const RadialLine& line, double lo, double hi,
                      std::span<double> out) const override {
    const double c = line.cos;
    if (std::abs(c) < 1e-12) return 0;
    const double rho = kCrease / c;
    if (!(rho >= lo && rho <= hi) || out.empty()) return 0;
    out[0] = rho;
    return 1;
  }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    const HeightDerivatives h = height_derivatives(x, y);
    z = h.z;
    zx = h.zx;
    zy = h.zy;
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    const bool a = x < kCrease;
    const double R = a ? kRA : kRB, u = x - (a ? kCrease - kEA : kCrease + kEB);
    const double w = std::sqrt(R * R - u * u - y * y), w3 = w * w * w;
    HeightDerivatives h;
    h.z = (a ? height_a() : height_b()) + w;
    h.zx = -u / w;
    h.zy = -y / w;
    h.zxx = -(R * R - y * y) / w3;
    h.zyy = -(R * R - u * u) / w3;
    h.zxy = -u * y / w3;
    return h;
  }
};

// The upper intersection of two circles (centre, radius).
Eigen::Vector2d upper_intersection(Eigen::Vector2d a, double ra, Eigen::Vector2d b, double rb) {
  const double d = (b - a).norm(), along = (ra * ra - rb * rb + d * d) / (2 * d);
  const double h = std::sqrt(ra * ra - along * along);
  const Eigen::Vector2d u = (b - a) / d, mid = a + along * u, perp(-u.y(), u.x());
  const Eigen::Vector2d p = mid + h * perp, q = mid - h * perp;
  return p.y() > q.y() ? p : q;
}

// A view of another surface: its shape and section creases, and the defaults for the
// bounds (no max_bend, no creases_near) unless a view below gives them.
struct SurfaceView : Surface {
  const Surface& s;
  explicit SurfaceView(const Surface& surface) : s(surface) {}
  const char* type() const override { return s.type(); }
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    s.sag_gradient(x, y, z, zx, zy);
  }
  HeightDerivatives height_derivatives(double x, double y) const override {
    return s.height_derivatives(x, y);
  }
  double defined_radius() const override { return s.defined_radius(); }
  bool has_creases() const override { return s.has_creases(); }
  int section_creases(const RadialLine& line, double lo, double hi,
                      std::span<double> out) const override {
    return s.section_creases(line, lo, hi, out);
  }
};

// A view that gives no bound of the design's bend (SurfaceView's max_bend, +∞): every crease
// search runs in full, the reference the bounded searches are compared with.
struct Unbounded final : SurfaceView {
  using SurfaceView::SurfaceView;
};

// The section along `line` at ρ: the design's height, its slope dz/dρ, and √(1 + slope²).
struct SectionPoint {
  double z, slope, l;
};
SectionPoint section_point(const Surface& s, const RadialLine& line, double rho) {
  double z, zx, zy;
  s.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
  const double slope = zx * line.cos + zy * line.sin;
  return {z, slope, std::sqrt(1 + slope * slope)};
}

SpiralOptions spiral_options(double outer, double pitch, double tolerance, double nose_radius) {
  SpiralOptions o;
  o.outer_radius = outer;
  o.pitch = pitch;
  o.points.tolerance = tolerance;
  o.tool.nose_radius = nose_radius;
  return o;
}

// Plans a spiral with the nose of radius o.tool.nose_radius and compensates every contact.
std::vector<CutterLocation> plan_with_nose(const Surface& s, const BaseSurface& base,
                                           const SpiralOptions& o,
                                           std::vector<ContactPoint>* contacts = nullptr,
                                           PathSummary* summary = nullptr) {
  ContactCollector out;
  const PathSummary planned = plan_spiral(s, base, o, out);
  if (summary) *summary = planned;
  CompensationOptions c;
  c.tool.nose_radius = o.tool.nose_radius;
  std::vector<CutterLocation> cls;
  for (const ContactPoint& p : out.points) cls.push_back(compensate(p, c));
  if (contacts) *contacts = std::move(out.points);
  return cls;
}

// The compound eye (extent 2.2 mm) as a space spiral over 1.6 mm on a least-squares
// base, with a 0.2 mm nose, ε = 0.2 µm, 4° angle cap.
std::vector<CutterLocation> plan_compound_eye(const LensletArray& eye, double pitch,
                                              std::vector<ContactPoint>* contacts,
                                              PathSummary* summary = nullptr,
                                              bool measure_every_crease = false) {
  SpiralOptions o = spiral_options(1.6, pitch, 2e-4, 0.2);
  o.points.max_angle_step = 4 * std::numbers::pi / 180;
  o.measure_every_crease = measure_every_crease;
  return plan_with_nose(eye, fit_base_least_squares(sample_aperture(eye, 0, 1.6)), o, contacts,
                        summary);
}

// What every spiral whose nose is held at creases must show: no jump, no point of the nose
// more than 10 nm below the design (the dense sampler), the chord within ε (2% for the
// sampler's own margin), and the nose held somewhere. Returns the worst uncut residual.
double check_held_spiral(const Surface& s, const std::vector<CutterLocation>& cls,
                         const std::vector<ContactPoint>& contacts, const PathSummary& summary,
                         double R, double tolerance) {
  CHECK(summary.jumps == 0);
  long held = 0;
  double worst_uncut = 0;
  for (const ContactPoint& p : contacts) {
    held += p.uncut_residual > 0;
    worst_uncut = std::max(worst_uncut, p.uncut_residual);
  }
  const test::DenseNoseFigures f = test::dense_nose_figures(s, cls, R, 12, 240);
  MESSAGE("points ", cls.size(), ", held ", held, ", deepest ", f.gouge * 1e6, " nm, chord ",
          f.worst * 1e6, " nm, uncut ", worst_uncut * 1e6, " nm");
  CHECK(f.gouge <= 10e-6);
  CHECK(f.worst <= tolerance * 1.02);
  CHECK(held > 0);
  return worst_uncut;
}

// The planner's own bound on the material a spiral leaves: its largest chord error above
// the design plus the larger of the scallop and the uncut residual.
double residual_bound(const std::vector<ContactPoint>& contacts) {
  double chord_above = 0, scallop = 0, uncut = 0;
  for (const ContactPoint& p : contacts) {
    if (!p.chord_below) chord_above = std::max(chord_above, p.chord_error);
    scallop = std::max(scallop, p.scallop);
    uncut = std::max(uncut, p.uncut_residual);
  }
  return chord_above + std::max(scallop, uncut);
}

// A hexagonal microlens array on a plane: lenses 0.5 mm across, 0.6 mm apart, to 1.5 mm.
LensletArray microlens_plate(double lens_radius) {
  LensletArrayOptions lo;
  lo.lens_radius = lens_radius;
  lo.lens_diameter = 0.5;
  lo.pitch = 0.6;
  lo.pattern = LensletArrayOptions::Pattern::kHexagonal;
  lo.extent = 1.5;
  return LensletArray(lo);
}

// Convex lenslets (R 0.3 mm unless given, D 0.2 mm) on a square 0.25 mm lattice over
// `extent`: flats 0.05 mm wide between rims, narrower than a 0.2 mm nose can reach into.
LensletArray close_lenslets(double extent, double lens_radius = -0.3) {
  LensletArrayOptions lo;
  lo.lens_radius = lens_radius;
  lo.lens_diameter = 0.2;
  lo.pitch = 0.25;
  lo.pattern = LensletArrayOptions::Pattern::kSquare;
  lo.extent = extent;
  return LensletArray(lo);
}

// Two plans with their blocks at the same angles.
bool same_blocks(const std::vector<ContactPoint>& a, const std::vector<ContactPoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (a[k].theta != b[k].theta) return false;
  return true;
}

}  // namespace

TEST_SUITE("path") {
  TEST_CASE("a concave crease: the nose held at the intersection of the two offsets, exactly") {
    const TwoDomes s;
    const double R = 0.2;
    const double xk = TwoDomes::kCrease;
    const Eigen::Vector2d oa(xk - TwoDomes::kEA, TwoDomes::height_a()),
        ob(xk + TwoDomes::kEB, TwoDomes::height_b());
    // Convex domes: each flank's offset is the concentric circle of radius R_dome + R.
    const Eigen::Vector2d K = upper_intersection(oa, TwoDomes::kRA + R, ob, TwoDomes::kRB + R);
    const Eigen::Vector2d touch_a = oa + TwoDomes::kRA * (K - oa).normalized();
    const Eigen::Vector2d touch_b = ob + TwoDomes::kRB * (K - ob).normalized();
    const double d = xk - K.x();
    const double uncut = K.y() - std::sqrt(R * R - d * d) - s.sag(xk, 0);

    for (const double rho :
         {xk - 0.012, xk - 0.004, xk - 1e-7, xk + 1e-7, xk + 0.003, xk + 0.009}) {
      CAPTURE(rho);
      const NoseTouch t = touch_at(s, rho, R);
      REQUIRE(t.held);
      CHECK(std::abs(t.centre_x - K.x()) < 1e-9);
      CHECK(std::abs(t.centre_z - K.y()) < 1e-9);
      const Eigen::Vector2d own = rho < xk ? touch_a : touch_b;
      const Eigen::Vector2d other = rho < xk ? touch_b : touch_a;
      CHECK(std::abs(t.rho - own.x()) < 1e-9);
      CHECK(std::abs(t.z - own.y()) < 1e-9);
      CHECK(std::abs(t.far_rho - other.x()) < 1e-8);
      CHECK(t.crease_rho == xk);
      CHECK(std::abs(t.uncut - uncut) < 1e-9);
      // Touching both flanks, below neither.
      CHECK(brute_overlap(s, t.centre_x, t.centre_z, R) <= 1e-9);
      CHECK(brute_overlap(s, t.centre_x, t.centre_z, R) >= -1e-9);
    }
    // The two ways to the held nose agree: Newton on the two offsets (a contact off the
    // crease) and the bracketing regula falsi (a contact within rounding of the crease,
    // whose flank is chosen by nose_touch and not by where the contact lies) meet at K,
    // each to 1e-12 mm of the closed form. A contact 5e-11 mm short of the crease carries
    // the near flank's slope: it was once left unheld, its nose over the far flank.
    for (const double rho : {xk - 5e-11, xk + 5e-11, xk - 0.004, xk + 0.003}) {
      CAPTURE(rho);
      const NoseTouch t = touch_at(s, rho, R);
      REQUIRE(t.held);
      CHECK(std::abs(t.centre_x - K.x()) < 1e-12);
      CHECK(std::abs(t.centre_z - K.y()) < 1e-12);
      CHECK((std::abs(t.rho - touch_a.x()) < 1e-11 || std::abs(t.rho - touch_b.x()) < 1e-11));
      CHECK(brute_overlap(s, t.centre_x, t.centre_z, R) <= 1e-9);
    }
    // Away from the crease the ordinary offset p + R·n̂ is safe and kept.
    for (const double rho : {xk - 0.05, xk - 0.02, xk + 0.02, xk + 0.3}) {
      CAPTURE(rho);
      const NoseTouch t = touch_at(s, rho, R);
      CHECK_FALSE(t.held);
      double z, zx, zy;
      s.sag_gradient(rho, 0, z, zx, zy);
      const double l = std::sqrt(1 + zx * zx);
      CHECK(t.centre_x == doctest::Approx(rho - R * zx / l).epsilon(1e-14));
      CHECK(t.centre_z == doctest::Approx(z + R / l).epsilon(1e-14));
      CHECK(brute_overlap(s, t.centre_x, t.centre_z, R) <= 1e-9);
    }
    // In the limit of flat flanks the residual is R(1/cos(δ/2) − 1); with these domes'
    // curvature it is a little less.
    const double delta =
        std::atan(TwoDomes::kEA /
                  std::sqrt(TwoDomes::kRA * TwoDomes::kRA - TwoDomes::kEA * TwoDomes::kEA)) +
        std::atan(TwoDomes::kEB /
                  std::sqrt(TwoDomes::kRB * TwoDomes::kRB - TwoDomes::kEB * TwoDomes::kEB));
    CHECK(uncut > 0.5 * R * (1 / std::cos(delta / 2) - 1));
    CHECK(uncut < 1.01 * R * (1 / std::cos(delta / 2) - 1) + 1e-6);
  }

  TEST_CASE(
      "a lenslet rim: the nose held at the intersection of the lens's and the base's offsets") {
    // The compound eye's central lenslet: its axis is the spindle axis, so in every radial
    // section the lens is a circle of radius 5 about (0, h − 5) (convex) and the base one of
    // radius 20 about (0, 20) (concave), meeting at the rim ρ = D/2 = 0.45. Their offsets
    // by R are the concentric circles of radii 5 + R and 20 − R. At θ = 30° the section
    // passes between the first ring's lenslets, so nothing else is under the nose.
    const LensletArray eye(test::compound_eye_options(3.0));
    const double R = 0.2, theta = std::numbers::pi / 6;
    const double h = (20 - std::sqrt(400 - 0.45 * 0.45)) + (5 - std::sqrt(25 - 0.45 * 0.45));
    const Eigen::Vector2d lens(0, h - 5), base(0, 20);
    const double r1 = 5 + R, r2 = 20 - R;
    const double kz = (r1 * r1 - r2 * r2 - lens.y() * lens.y() + base.y() * base.y()) /
                      (2 * (base.y() - lens.y()));
    const Eigen::Vector2d K(std::sqrt(r1 * r1 - (kz - lens.y()) * (kz - lens.y())), kz);
    const Eigen::Vector2d on_lens = lens + 5 * (K - lens).normalized();
    const Eigen::Vector2d on_base = base + 20 * (K - base).normalized();
    CHECK(on_lens.x() < 0.45);
    CHECK(on_base.x() > 0.45);
    for (const double rho : {0.447, 0.4499, 0.4501, 0.452}) {
      CAPTURE(rho);
      double z, zx, zy;
      eye.sag_gradient(rho * std::cos(theta), rho * std::sin(theta), z, zx, zy);
      const NoseTouch t =
          nose_touch(eye, theta, R, rho, z, zx * std::cos(theta) + zy * std::sin(theta));
      REQUIRE(t.held);
      CHECK(std::abs(t.crease_rho - 0.45) < 1e-12);
      CHECK(std::abs(t.centre_x - K.x()) < 1e-9);
      CHECK(std::abs(t.centre_z - K.y()) < 1e-9);
      const Eigen::Vector2d own = rho < 0.45 ? on_lens : on_base,
                            other = rho < 0.45 ? on_base : on_lens;
      CHECK(std::abs(t.rho - own.x()) < 1e-9);
      CHECK(std::abs(t.far_rho - other.x()) < 1e-8);
      const double d = 0.45 - K.x();
      const double rim_z = h - 5 + std::sqrt(25 - 0.45 * 0.45);
      CHECK(std::abs(t.uncut - (K.y() - std::sqrt(R * R - d * d) - rim_z)) < 1e-9);
    }
  }

  TEST_CASE(
      "flanks skipped by the concavity bound: the same holds, and overlaps to 1 pm of brute "
      "force") {
    // Surface::max_bend lets the crease searches skip a flank that cannot rise to the best
    // value found, and a piece already searched whose ceiling shows it rising no more than
    // 1e-13 mm above it (section_envelope.cpp); the same bound tells a search whose first
    // steps stopped short that the piece may still rise, and it goes on (kSettled). The
    // same searches on a view of the same array that gives no bound (max_bend = +inf:
    // every flank searched, three steps each) must give the same holds (centres to 1e-9
    // mm), and overlaps no lower than that view's but by 1 pm (below), so never further from
    // brute force (4 001 values across the nose, then ternary search), for noses placed at
    // random a few micrometres about the design near the rims, on domes and on bowls.
    // Before searches went on, the bounded answers equalled the view's bits. The view's
    // search from the hint now goes on too, by secant steps until the peak it predicts is
    // within kSettled (1 pm) of the best found, so the two agree to that 1 pm, not to 1e-13
    // mm; the view's crease searches (no bound to settle by) still fall short of brute force
    // by the fourth-order term of a search's last step (up to 3.7 pm here).
    for (const double lens_radius : {-5.0, 1.5}) {
      LensletArrayOptions options = test::compound_eye_options(3.0);
      options.lens_radius = lens_radius;
      const LensletArray eye(options);
      const Unbounded plain(eye);
      REQUIRE(std::isfinite(eye.max_bend(3.2)));
      REQUIRE(std::isinf(plain.max_bend(3.2)));
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> unit(0, 1);
      const double R = 0.2;
      int differ = 0, held = 0, overlaps = 0, short_of_brute = 0, plain_short = 0, brute = 0;
      double worst_short = 0, worst_plain = 0;
      for (int k = 0; k < 20000; ++k) {
        const double theta = 2 * std::numbers::pi * unit(rng), rho = 0.1 + 2.6 * unit(rng);
        const RadialLine line(theta);
        const auto [z, slope, l] = section_point(eye, line, rho);
        const NoseTouch a = nose_touch(eye, line, R, rho, z, slope);
        const NoseTouch b = nose_touch(plain, line, R, rho, z, slope);
        differ += a.held != b.held || std::abs(a.centre_x - b.centre_x) > 1e-9 ||
                  std::abs(a.centre_z - b.centre_z) > 1e-9 || std::abs(a.uncut - b.uncut) > 1e-9;
        held += a.held;
        // A nose at the contact's offset, moved by up to ±2 µm in each direction.
        const double x_c = rho - R * slope / l + 4e-3 * (unit(rng) - 0.5);
        const double z_c = z + R / l + 4e-3 * (unit(rng) - 0.5);
        const NoseOverlap o = nose_overlap(eye, line, x_c, z_c, R, rho);
        const NoseOverlap p = nose_overlap(plain, line, x_c, z_c, R, rho);
        differ += !(o.height >= p.height - 1e-9 - 1e-15);
        overlaps += o.height > 0;
        if (k % 10 == 0) {
          const double truth = brute_overlap(eye, x_c, z_c, R, theta, 4000);
          ++brute;
          short_of_brute += o.height < truth - 2e-9;
          plain_short += p.height < truth - 2e-9;
          worst_short = std::max(worst_short, truth - o.height);
          worst_plain = std::max(worst_plain, truth - p.height);
        }
      }
      MESSAGE("lens radius ", lens_radius, ": ", held, " holds, ", overlaps, " overlaps; of ",
              brute, " against brute force, ", short_of_brute,
              " short by more than 2 pm (three steps a flank: ", plain_short, "); the most short ",
              worst_short * 1e9, " pm (", worst_plain * 1e9, " pm)");
      CHECK(differ == 0);
      // Never further from brute force than searching every flank; often nearer.
      CHECK(short_of_brute <= plain_short);
      CHECK(worst_short <= worst_plain + 1e-13);
      if (lens_radius < 0) CHECK(held > 100);  // bowls' rims are ridges: nothing to hold
      CHECK(overlaps > 1000);
    }
  }

  TEST_CASE("across a concave crease the nose centre moves continuously and forward, never below") {
    const TwoDomes s;
    const double R = 0.2, xk = TwoDomes::kCrease;
    double previous_x = -1e300, previous_z = 0;
    int held = 0;
    for (int i = 0; i <= 800; ++i) {
      const double rho = xk - 0.04 + 0.0001 * i;
      const NoseTouch t = touch_at(s, rho, R);
      held += t.held;
      CHECK(brute_overlap(s, t.centre_x, t.centre_z, R) <= 1e-9);
      if (i > 0) {
        CHECK(t.centre_x >= previous_x - 1e-12);
        // No jump: a step of 0.1 µm in the contact moves the centre at most a few times as far.
        CHECK(std::hypot(t.centre_x - previous_x, t.centre_z - previous_z) <= 1e-3);
      }
      previous_x = t.centre_x;
      previous_z = t.centre_z;
    }
    CHECK(held > 100);  // about R·tan(δ/2) on each side, 0.1 µm apart
  }

  TEST_CASE(
      "bowls bending a little more than the nose: pieces left on the parabola bound, the same "
      "answers") {
    // Bowls whose walls bend more than the nose along a section (g'' = 1/(r cos³ψ) at the
    // rim's slope; 3 % more under a 0.107 mm nose) give no concavity bound, and each piece the nose
    // may overhang is searched from both its ends. A piece whose first value's parabola (h'' ≤
    // max_bend − 1/R) stays under the tolerance, or under the largest height found, is left after
    // that value (section_envelope.cpp, search). The same contacts and noses on a view of the array
    // that gives no bound (every piece searched from both ends) must give the same placements and
    // the same overlaps, and no placed nose may overhang the section (brute force, 4 001 values
    // across the nose, then ternary search).
    LensletArrayOptions options;
    options.lens_radius = 0.1466;  // bowls
    options.lens_diameter = 0.1335;
    options.pitch = 0.1697;
    options.pattern = LensletArrayOptions::Pattern::kHexagonal;
    options.extent = 0.5;
    const LensletArray bowls(options);
    const Unbounded plain(bowls);
    // Noses of 0.107 to 0.3 mm: the walls' g'' exceeds 1/R by 0.3 to 6.4 /mm, so a piece's
    // parabola rises 2.6 to 56 µm above its tangent over a bowl's width. (On these bowls no
    // far end rises above what the near search found: taking the parabola as its tangent
    // changes none of these answers. The grid's case below does.)
    for (const double R : {0.1067, 0.14, 0.2, 0.3}) {
      const double up = bowls.max_bend(0.5) - 1 / R;
      REQUIRE(up > 0);  // no concavity bound, but a finite rise bound: what the parabola serves
      REQUIRE(std::isinf(plain.max_bend(0.5)));
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> unit(0, 1);
      int differ = 0, overhung = 0, brute = 0;
      double deepest = -1;
      for (int k = 0; k < 6000; ++k) {
        const double theta = 2 * std::numbers::pi * unit(rng), rho = 0.02 + 0.36 * unit(rng);
        const RadialLine line(theta);
        const auto [z, slope, l] = section_point(bowls, line, rho);
        const NoseTouch a = nose_touch(bowls, line, R, rho, z, slope);
        const NoseTouch b = nose_touch(plain, line, R, rho, z, slope);
        differ += a.held != b.held || a.centre_x != b.centre_x || a.centre_z != b.centre_z ||
                  a.uncut != b.uncut;
        const double x_c = rho - R * slope / l + 4e-3 * (unit(rng) - 0.5);
        const double z_c = z + R / l + 4e-3 * (unit(rng) - 0.5);
        const NoseOverlap o = nose_overlap(bowls, line, x_c, z_c, R, rho);
        const NoseOverlap p = nose_overlap(plain, line, x_c, z_c, R, rho);
        differ += std::abs(o.height - p.height) > 1e-15;
        if (k % 6 == 0) {
          const double depth = brute_overlap(bowls, a.centre_x, a.centre_z, R, theta, 4000);
          ++brute;
          overhung += depth > 1e-9;
          deepest = std::max(deepest, depth);
        }
      }
      MESSAGE("nose ", R, " mm: ", differ, " answers differ; of ", brute,
              " placements against brute force the deepest ", deepest * 1e6, " nm");
      CHECK(differ == 0);
      CHECK(overhung == 0);
    }
  }

  TEST_CASE(
      "a grid's troughs barely tighter than the nose: pieces left on the parabola bound, the "
      "same answers") {
    // The grid A 5 µm, λ 0.3 × 0.4 mm bends to 1/(A k²) = 0.456 mm at most (max_bend) under a
    // 0.5 mm nose, so the troughs' view lists creases and the pieces between them have no
    // concavity bound, but h'' ≤ 0.19 /mm on them. Contacts on 48 lines, each placed through
    // the view of the grid and through the view of a copy that gives no bound (every piece
    // searched from both its ends): the same placements and, for noses moved about them, the
    // same overlaps; and no placed nose overhangs the grid (brute force about R').
    const SinusoidalGrid grid(0.005, 0.3, 0.4);
    const Unbounded plain(grid);
    const double R = 0.5, stand_off = 5e-5, placed = R + stand_off;
    REQUIRE(grid.max_bend(1.5) * placed > 1);
    REQUIRE(grid.max_bend(1.5) - 1 / R < 0.2);
    const TightTroughs bounded(grid, placed, 1.5), unbounded(plain, placed, 1.5);
    REQUIRE(bounded.any());
    REQUIRE(unbounded.any());
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    int differ = 0, held = 0, overhung = 0, contacts = 0;
    double deepest = -1;
    for (int k = 0; k < 48; ++k) {
      const RadialLine line(0.013 + k * 2 * std::numbers::pi / 48);
      for (int i = 0; i < 60; ++i, ++contacts) {
        const double rho = 0.05 + 1.35 * unit(rng);
        const auto [z, slope, l] = section_point(grid, line, rho);
        const NoseTouch a = nose_touch(bounded, line, R, rho, z, slope, stand_off);
        const NoseTouch b = nose_touch(unbounded, line, R, rho, z, slope, stand_off);
        differ += a.held != b.held || a.centre_x != b.centre_x || a.centre_z != b.centre_z;
        held += a.held;
        const double depth = brute_overlap(grid, a.centre_x, a.centre_z, placed, line.theta, 4000);
        overhung += depth > 1e-9;
        deepest = std::max(deepest, depth);
        const double x_c = rho - placed * slope / l + 4e-3 * (unit(rng) - 0.5);
        const double z_c = z + placed / l + 4e-3 * (unit(rng) - 0.5);
        const NoseOverlap o = nose_overlap(bounded, line, x_c, z_c, placed, rho);
        const NoseOverlap p = nose_overlap(unbounded, line, x_c, z_c, placed, rho);
        differ += std::abs(o.height - p.height) > 1e-15;
      }
    }
    MESSAGE(contacts, " contacts, ", held, " held, ", differ, " answers differ; the deepest nose ",
            deepest * 1e6, " nm");
    CHECK(differ == 0);
    CHECK(held > 20);
    CHECK(overhung == 0);
  }

  TEST_CASE(
      "a sinusoidal ring's radial sections bend at most |A|ω²: the searches left on that bound "
      "give the same answers") {
    // Off its radial sections the ring has no bound (max_bend +∞: just off the cone point a
    // line bends without limit), along them |A|ω² (max_section_bend). The tight ring (A 50 µm,
    // period 0.8 mm: 3.08 /mm under a 0.5 mm nose, its troughs tighter than the nose) gives
    // the parabola h'' ≤ 1.08 /mm: placements and overlaps the same to the bit as through a
    // view of it with no bound. The gentle ring (A 5 µm, period 2.5 mm: 0.032 /mm) gives a
    // concavity bound, under which a search settles to kSettled (1 pm) of its peak by Newton
    // steps instead of the secant's: the overlaps agree to that, either way (83 of 1 440
    // higher, the most 0.48 pm lower). Contacts on 24 lines from the cone point out to 1.5
    // mm; no placed nose overhangs the ring (brute force about R').
    const double R = 0.5, stand_off = 5e-5, placed = R + stand_off;
    for (const auto& [a, period] : {std::array{0.05, 0.8}, std::array{0.005, 2.5}}) {
      CAPTURE(a);
      const double w = 2 * std::numbers::pi / period;
      const SinusoidalRing ring(a, w, 0.0);
      const Unbounded plain(ring);
      REQUIRE(std::isinf(ring.max_bend(1.0)));
      REQUIRE(ring.max_section_bend(1.0) == doctest::Approx(a * w * w));
      const bool tight = a * w * w * placed > 1;
      const TightTroughs bounded(ring, placed, 1.5), unbounded(plain, placed, 1.5);
      REQUIRE(bounded.any() == tight);
      std::mt19937 rng(13);
      std::uniform_real_distribution<double> unit(0, 1);
      int differ = 0, overhung = 0, contacts = 0;
      double apart = 0, deepest = -1;
      for (int k = 0; k < 24; ++k) {
        const RadialLine line(0.021 + k * 2 * std::numbers::pi / 24);
        for (int i = 0; i < 60; ++i, ++contacts) {
          const double rho = 0.01 + 1.45 * unit(rng);
          const auto [z, slope, l] = section_point(ring, line, rho);
          const NoseTouch t = nose_touch(bounded, line, R, rho, z, slope, stand_off);
          const NoseTouch u = nose_touch(unbounded, line, R, rho, z, slope, stand_off);
          if (tight)
            differ += t.held != u.held || t.centre_x != u.centre_x || t.centre_z != u.centre_z;
          const double depth =
              brute_overlap(ring, t.centre_x, t.centre_z, placed, line.theta, 4000);
          overhung += depth > 1e-9;
          deepest = std::max(deepest, depth);
          const double x_c = rho - placed * slope / l + 4e-3 * (unit(rng) - 0.5);
          const double z_c = z + placed / l + 4e-3 * (unit(rng) - 0.5);
          const NoseOverlap o = nose_overlap(bounded, line, x_c, z_c, placed, rho);
          const NoseOverlap p = nose_overlap(unbounded, line, x_c, z_c, placed, rho);
          if (tight) differ += o.height != p.height;
          apart = std::max(apart, std::abs(o.height - p.height));
        }
      }
      MESSAGE(contacts, " contacts, ", differ, " answers differ, overlaps at most ", apart * 1e9,
              " pm apart; the deepest nose ", deepest * 1e6, " nm");
      CHECK(differ == 0);
      CHECK(apart <= 1e-9);  // kSettled
      CHECK(overhung == 0);
    }
  }

  TEST_CASE("a nose that just fits the design's concavity: the overlap searched to its peak") {
    // A sinusoidal grid (20 µm, 0.8 mm) bends toward the tool up to 1/0.81 mm⁻¹ across its
    // troughs; under a 0.75 mm nose the height of the section over the lower arc is then
    // only weakly concave, and steps that take its h'' as the nose's alone cover a tenth of
    // the way to the peak. The first case is a nose as a chord-planned spiral's segment
    // interpolated it (C 155.045°, 0.711 of the way between two blocks): two such steps
    // read 0.10 nm of overlap where the nose cuts 4.14 nm into the design.
    const SinusoidalGrid grid(0.02, 0.8, 0.8);
    const double R = 0.75;
    {
      const double t = 0.711, x = 2.069324 + t * (2.088561 - 2.069324),
                   z = 0.735688 + t * (0.743615 - 0.735688);
      const RadialLine line((153.6579 + t * (155.60928 - 153.6579)) * std::numbers::pi / 180);
      const double brute = brute_overlap(grid, x, z, R, line.theta);
      MESSAGE("the segment's nose: " << brute * 1e6 << " nm into the design");
      CHECK(brute == doctest::Approx(4.14e-6).epsilon(0.01));
      CHECK(std::abs(nose_overlap(grid, line, x, z, R, 2.1158).height - brute) <= 2e-9);
      CHECK(std::abs(nose_overlap_near(grid, line, x, z, R, 2.1158).height - brute) <= 2e-9);
    }
    // A sweep: noses placed on the offset of a touch at ρ₀ and moved as a chord moves them
    // (up to 20 µm across and 0.2 µm down), searched from ρ₀, against brute force.
    std::mt19937 random(29);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double shortest = 0;
    for (int i = 0; i < 400; ++i) {
      const RadialLine line(2 * std::numbers::pi * unit(random));
      const double rho0 = 0.5 + 2.5 * unit(random);
      double g, gx, gy;
      grid.sag_gradient(rho0 * line.cos, rho0 * line.sin, g, gx, gy);
      const double slope = gx * line.cos + gy * line.sin, l = std::sqrt(1 + slope * slope);
      const double x = rho0 - R * slope / l + 2e-2 * (unit(random) - 0.5);
      const double z = g + R / l - 2e-4 * unit(random);
      const double brute = brute_overlap(grid, x, z, R, line.theta);
      const NoseOverlap o = nose_overlap(grid, line, x, z, R, rho0);
      const NoseOverlap near = nose_overlap_near(grid, line, x, z, R, rho0);
      CHECK(o.height <= brute + 1e-12);
      CHECK(near.height == o.height);
      shortest = std::max(shortest, brute - o.height);
    }
    MESSAGE("the searches fall short of brute force by " << shortest * 1e9 << " pm at most");
    CHECK(shortest <= 2e-9);
  }

  TEST_CASE("the overlap finds a crease's sharp peak that a sampled arc steps over") {
    const TwoDomes s;
    const double R = 0.2, xk = TwoDomes::kCrease;
    // The ordinary offset just before the crease overhangs the other flank.
    double z, zx, zy;
    const double rho = xk - 0.002;
    s.sag_gradient(rho, 0, z, zx, zy);
    const double l = std::sqrt(1 + zx * zx);
    const double cx = rho - R * zx / l, cz = z + R / l;
    const NoseOverlap o = nose_overlap(s, 0.0, cx, cz, R, rho);
    const double brute = brute_overlap(s, cx, cz, R);
    CHECK(brute > 1e-4);
    CHECK(o.height == doctest::Approx(brute).epsilon(1e-7));
  }

  TEST_CASE("compound eye: a touch clear of creases touches nowhere else and is not held") {
    // Random contacts on the compound eye (0.9 mm lenslets on a 20 mm base), a 0.2 mm nose
    // placed at each contact's plain offset. Where touch_clear_of_creases holds with a
    // 10 µm margin, the nose at that contact, and at contacts up to 10 µm either way along
    // the radial line, overhangs the section nowhere (brute force over 20 000 radii),
    // nose_touch does not hold it, and a nose 1 µm across and 0.1 µm above it finds the
    // same overlap with and without the crease search, to 10 pm. The envelope is not empty either:
    // a third of the contacts are clear, none within 10 µm of a rim (lenslet_at along
    // the line), and some that are not clear do overhang.
    const LensletArray eye(test::compound_eye_options(3.0));
    const double R = 0.2, margin = 10e-3;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    const auto centre_of = [&](const RadialLine& line, double rho, double& cx, double& cz) {
      double z, zx, zy;
      eye.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const double slope = zx * line.cos + zy * line.sin, l = std::sqrt(1 + slope * slope);
      cx = rho - R * slope / l;
      cz = z + R / l;
      return slope;
    };
    int clear = 0, overhanging_unclear = 0, near_rim_clear = 0;
    double worst_difference = 0;
    const int n = 400;
    for (int k = 0; k < n; ++k) {
      const double theta = 2 * std::numbers::pi * unit(rng), rho = 0.05 + 2.2 * unit(rng);
      const RadialLine line(theta);
      double cx, cz;
      centre_of(line, rho, cx, cz);
      const bool is_clear = touch_clear_of_creases(eye, rho * line.cos, rho * line.sin, R, margin);
      if (!is_clear) {
        overhanging_unclear += brute_overlap(eye, cx, cz, R, theta, 4000) > 1e-9;
        continue;
      }
      ++clear;
      const int own = eye.lenslet_at(rho * line.cos, rho * line.sin);
      for (double d = -margin; d <= margin + 1e-12; d += 1e-4)
        near_rim_clear += eye.lenslet_at((rho + d) * line.cos, (rho + d) * line.sin) != own;
      for (const double d : {-margin, -0.5 * margin, 0.0, 0.5 * margin, margin}) {
        CAPTURE(theta);
        CAPTURE(rho + d);
        double x, z;
        const double slope = centre_of(line, rho + d, x, z);
        CHECK(brute_overlap(eye, x, z, R, theta) <= 1e-10);
        double sz, zx, zy;
        eye.sag_gradient((rho + d) * line.cos, (rho + d) * line.sin, sz, zx, zy);
        CHECK_FALSE(nose_touch(eye, line, R, rho + d, sz, slope).held);
        const NoseOverlap full = nose_overlap(eye, line, x + 1e-3, z + 1e-4, R, rho + d);
        const NoseOverlap near = nose_overlap_near(eye, line, x + 1e-3, z + 1e-4, R, rho + d);
        // The same but for the Newton steps' shortfall: the hint lies 1 µm from the touch
        // here (the planner's within nanometres), and the full search's crease searches on
        // the touch's own piece can only add steps toward its top. Both settle to 1 pm of
        // it (kSettled: the full one by the concavity bound, the near one by its secant),
        // so the near one may end up to that much higher.
        CHECK(full.height >= near.height - 1e-9);
        CHECK(full.height - near.height <= 1e-8);
        worst_difference = std::max(worst_difference, full.height - near.height);
      }
    }
    MESSAGE("clear ", clear, " of ", n, ", not clear and overhanging ", overhanging_unclear,
            ", overlap with the crease search over without, at most ", worst_difference * 1e9,
            " pm");
    CHECK(clear > n / 3);
    CHECK(near_rim_clear == 0);
    CHECK(overhanging_unclear > 0);
  }

  TEST_CASE(
      "lenslet arrays: touches near a rim that the rims' directions clear touch nowhere else") {
    // Random touches within 40 µm of a rim (a change of lenslet_at on a 40 µm circle about
    // them), margins of 0, 3 and 10 µm. Where touch_clear_of_creases holds, the nose placed at
    // the plain offset of the touch and of eight touches on the margin's circle about it,
    // each on its own radial line, overhangs the section nowhere (brute force over 20 000
    // radii) and is not held. The same array with the rims' directions withheld (each
    // crease bounded along any direction, as before they were told) must clear no touch the
    // full one does not, and the full one must clear more: domes on a concave base, bowls
    // on a convex one, domes on a plane.
    struct WithoutDirections final : SurfaceView {
      using SurfaceView::SurfaceView;
      double max_bend(double radius) const override { return s.max_bend(radius); }
      int creases_near(double x, double y, double radius,
                       std::span<NearbyCrease> out) const override {
        const int count = s.creases_near(x, y, radius, out);
        for (int k = 0; k < count; ++k) out[static_cast<std::size_t>(k)].centre_distance = 0;
        return count;
      }
    };
    struct Case {
      double base_curvature, lens_radius;
    };
    for (const Case c : {Case{1 / 20.0, -5.0}, Case{1 / 20.0, 1.5}, Case{0.0, -1.5}}) {
      CAPTURE(c.base_curvature);
      CAPTURE(c.lens_radius);
      LensletArrayOptions o = test::compound_eye_options(3.0);
      o.base_curvature = c.base_curvature;
      o.lens_radius = c.lens_radius;
      const LensletArray array(o);
      const WithoutDirections plain(array);
      const double R = 0.2;
      std::mt19937 rng(17);
      std::uniform_real_distribution<double> unit(0, 1);
      int tried = 0, cleared = 0, cleared_plain = 0, only_plain = 0, checked = 0;
      for (int k = 0; tried < 600 && k < 200000; ++k) {
        const double r = 2.3 * std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        const int own = array.lenslet_at(x, y);
        bool near_rim = false;
        for (int j = 0; j < 16 && !near_rim; ++j) {
          const double a = 2 * std::numbers::pi * j / 16;
          near_rim = array.lenslet_at(x + 0.04 * std::cos(a), y + 0.04 * std::sin(a)) != own;
        }
        if (!near_rim) continue;
        const double margin = std::array<double, 3>{0.0, 3e-3, 10e-3}[tried % 3];
        ++tried;
        const bool clear = touch_clear_of_creases(array, x, y, R, margin);
        const bool clear_plain = touch_clear_of_creases(plain, x, y, R, margin);
        cleared += clear;
        cleared_plain += clear_plain;
        only_plain += clear_plain && !clear;
        if (!clear) continue;
        for (int j = -1; j < 8; ++j) {
          const double a = 2 * std::numbers::pi * j / 8;
          const double tx = j < 0 ? x : x + margin * std::cos(a);
          const double ty = j < 0 ? y : y + margin * std::sin(a);
          const double theta = std::atan2(ty, tx), rho = std::hypot(tx, ty);
          const RadialLine line(theta);
          double z, zx, zy;
          array.sag_gradient(tx, ty, z, zx, zy);
          const double slope = zx * line.cos + zy * line.sin, l = std::sqrt(1 + slope * slope);
          const double cx = rho - R * slope / l, cz = z + R / l;
          CAPTURE(tx);
          CAPTURE(ty);
          CAPTURE(margin);
          CHECK(brute_overlap(array, cx, cz, R, theta) <= 1e-10);
          CHECK_FALSE(nose_touch(array, line, R, rho, z, slope).held);
          ++checked;
        }
      }
      MESSAGE("near a rim: ", tried, " touches, cleared ", cleared, " (", cleared_plain,
              " with the rims' directions withheld), noses checked ", checked);
      CHECK(tried == 600);
      CHECK(only_plain == 0);
      CHECK(cleared >= cleared_plain + 15);
    }
  }

  TEST_CASE("compound eye, space spiral with a nose: no point of the nose below the design") {
    // Planned as it is (segments clear of creases measured as on a smooth design) and with
    // every segment measured in full: both must pass the dense sampler.
    const LensletArray eye(test::compound_eye_options(2.2));
    const double R = 0.2;
    for (const bool every : {false, true}) {
      CAPTURE(every);
      std::vector<ContactPoint> contacts;
      PathSummary summary;
      const std::vector<CutterLocation> cls =
          plan_compound_eye(eye, 0.05, &contacts, &summary, every);
      const double worst_uncut = check_held_spiral(eye, cls, contacts, summary, R, 2e-4);
      // The rims' angle in the radial section is at most the 3D crease angle (about 6.5°):
      // under the real nose the residual stays below (R + ε/2)/cos(δ/2) − R for δ = 7°, the
      // nose standing off ε/2.
      const double lifted = R + 0.5 * 2e-4;  // the nose stands off ε/2 (plan_compound_eye)
      CHECK(worst_uncut < lifted / std::cos(3.5 * std::numbers::pi / 180) - R);
    }
  }

  TEST_CASE("compound eye at 50 nm: segments clear of creases measured as smooth, as safe") {
    // At ε = 50 nm beyond the first ring of lenslets the steps away from the rims are set
    // by the chord, not the angle cap (inside it the central lenslet is turned true),
    // so measuring the segments clear of creases (path_stepper.hpp) as on a smooth design
    // (8 intervals, no crease search, no slide) moves blocks: the plan differs from the one
    // with every segment measured in full. Both must pass the dense sampler (no gouge over
    // 10 nm, the chord within ε and 2 %) and the brute-force cut (what is left within the
    // planner's own bound), and cost about as many points.
    const LensletArray eye(test::compound_eye_options(3.0));
    const double R = 0.2, tolerance = 5e-5, outer = 2.2;
    SpiralOptions o = spiral_options(outer, 0.04, tolerance, R);
    o.points.max_angle_step = 4 * std::numbers::pi / 180;
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, outer));
    std::size_t points[2] = {0, 0};
    std::vector<ContactPoint> plans[2];
    for (const bool every : {false, true}) {
      CAPTURE(every);
      o.measure_every_crease = every;
      std::vector<ContactPoint>& contacts = plans[every];
      PathSummary summary;
      const std::vector<CutterLocation> cls = plan_with_nose(eye, base, o, &contacts, &summary);
      points[every] = cls.size();
      check_held_spiral(eye, cls, contacts, summary, R, tolerance);
      const double bound = residual_bound(contacts);
      const double left = test::dense_spiral_residual(eye, cls, R, 360, 0.1, 2.15, 0.0025);
      MESSAGE("left ", left * 1e6, " nm, bound ", bound * 1e6, " nm");
      CHECK(left <= bound);
    }
    CHECK_FALSE(same_blocks(plans[0], plans[1]));
    CHECK(static_cast<double>(points[0]) <= 1.02 * static_cast<double>(points[1]));
    CHECK(static_cast<double>(points[0]) >= 0.98 * static_cast<double>(points[1]));
  }

  TEST_CASE("compound eye, PVT: segments clear of creases measured as smooth, as safe") {
    // The controller's cubics (PVT) on the compound eye, planned with the segments clear of
    // creases measured as on a smooth design and with every segment measured in full. The
    // dense sampler of the cubics (dense_check.hpp, written apart from the planner) must
    // find no gouge over 10 nm and the chord within ε either way (a spiral's PVT peaks are
    // searched as linear ones are, docs/path.md), and the plans differ.
    const LensletArray eye(test::compound_eye_options(3.0));
    const double R = 0.2, tolerance = 1e-4, outer = 2.2;
    SpiralOptions o = spiral_options(outer, 0.05, tolerance, R);
    o.points.max_angle_step = 4 * std::numbers::pi / 180;
    o.points.interpolation = Interpolation::kCubic;
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, outer));
    std::vector<ContactPoint> plans[2];
    for (const bool every : {false, true}) {
      CAPTURE(every);
      o.measure_every_crease = every;
      PathSummary summary;
      const std::vector<CutterLocation> cls = plan_with_nose(eye, base, o, &plans[every], &summary);
      CHECK(summary.jumps == 0);
      const test::DenseNoseFigures f =
          test::dense_nose_figures(eye, cls, R, 50, 240, nullptr, true);
      MESSAGE("points ", cls.size(), ", deepest ", f.gouge * 1e6, " nm, chord ", f.worst * 1e6,
              " nm");
      CHECK(f.gouge <= 10e-6);
      CHECK(f.worst <= tolerance);
    }
    CHECK_FALSE(same_blocks(plans[0], plans[1]));
  }

  TEST_CASE("a spiral across a crease: a block where each hold begins and ends") {
    // A traditional spiral (plane base) over a V-groove (a NURBS seam): the contact the
    // path asks for at θ is ρ(θ) = r_outer − pθ/2π, and the nose is held wherever its
    // plain offset there (radius R + ε/2, the band's stand-off) would overhang the far
    // flank, found here by brute force (brute_overlap) and bisection in θ to 1e-12 rad.
    const NurbsHeightField s(test::v_groove(0.5, 0.1115));
    const double R = 0.2, tolerance = 2e-4, lifted = R + 0.5 * tolerance, outer = 1.2;
    SpiralOptions o = spiral_options(outer, 0.05, tolerance, R);
    std::vector<ContactPoint> contacts;
    const std::vector<CutterLocation> cls =
        plan_with_nose(s, BaseSurface::plane(outer), o, &contacts);
    const auto held_at = [&](double theta) {
      const double rho = outer - o.pitch * theta / (2 * std::numbers::pi);
      const double ct = std::cos(theta), st = std::sin(theta);
      double z, zx, zy;
      s.sag_gradient(rho * ct, rho * st, z, zx, zy);
      const double slope = zx * ct + zy * st, l = std::sqrt(1 + slope * slope);
      return brute_overlap(s, rho - lifted * slope / l, z + lifted / l, lifted, theta, 1000) >
             1e-10;
    };
    int changes = 0, on_block = 0;
    for (std::size_t k = 1; k < contacts.size(); ++k) {
      const double ta = contacts[k - 1].theta, tb = contacts[k].theta;
      if ((contacts[k - 1].uncut_residual > 0) == (contacts[k].uncut_residual > 0)) continue;
      ++changes;
      const bool held_a = held_at(ta);
      double lo = ta, hi = tb;
      while (hi - lo > 1e-12) {
        const double mid = 0.5 * (lo + hi);
        (held_at(mid) == held_a ? lo : hi) = mid;
      }
      // The block is there to the program's resolution (end_at_hold_change stops within
      // 1 nm of axis travel of the change, of which the arc of C at the nose centre's
      // radius, at least ρ − R − ε/2, is a part), or the change lies within a tenth of the
      // step after the block before it, where the planner leaves it: a block there would be
      // a sliver (path_stepper.hpp).
      const double at = (hi - ta) / (tb - ta);
      const double centre_radius = outer - o.pitch * hi / (2 * std::numbers::pi) - lifted;
      if (std::abs(tb - hi) * std::max(centre_radius, 0.0) <= 1e-6 + 1e-12) {
        ++on_block;
      } else {
        CHECK(at <= 0.1 + 1e-6);
      }
    }
    MESSAGE("points ", contacts.size(), ", hold changes ", changes, ", on a block ", on_block);
    CHECK(changes > 10);
    CHECK(on_block >= changes / 2);
  }

  TEST_CASE("compound eye, space spiral: the material left stays within the prediction") {
    // Where a rim crosses the spiral obliquely the path's nose changes flank within a few
    // degrees of C; a chord across that change keeps the nose touching the design but far
    // from the path's own touch, and the cusp to the next pass grows with it (1.1 µm on the
    // demo job against 0.62 µm predicted, before the planner measured the slide). Cut here
    // by brute force and compared with the planner's own bound: the largest chord error
    // above the design plus the larger of the scallop and the uncut residual.
    // Segments whose nose stays clear of every crease are measured without the slide (as
    // on a smooth design); with every segment measured in full as well.
    const LensletArray eye(test::compound_eye_options(2.2));
    const double R = 0.2;
    for (const bool every : {false, true}) {
      CAPTURE(every);
      std::vector<ContactPoint> contacts;
      const std::vector<CutterLocation> cls =
          plan_compound_eye(eye, 0.02, &contacts, nullptr, every);
      const double bound = residual_bound(contacts);
      // Inside the outermost and innermost turns, where two passes bracket every radius.
      const double left = test::dense_spiral_residual(eye, cls, R, 360, 0.1, 1.55, 0.0025);
      MESSAGE("points ", cls.size(), ", left ", left * 1e6, " nm, bound ", bound * 1e6, " nm");
      CHECK(left > 0);
      CHECK(left <= bound);
    }
  }

  TEST_CASE(
      "chord rule on the compound eye: each block's error holds the slide of the path's own "
      "noses") {
    // The slide (Path::slide) is the interpolated nose's rise over the path's own nose at
    // the same angle, across the half pitch either side of that nose's touch. Re-derived
    // here from outside the planner: the path's own noses at 20 000 angles a turn come from
    // an equal-angle plan of the same path (its nose raised by the chord rule's stand-off,
    // which equal angles do not take, so that both place the same envelope), the
    // interpolated nose from the chord plan's blocks, linear in C; each segment's largest
    // rise there must stay within the error the planner reports for it (0.5 % for its
    // peak search, 1 pm for the two plans' rounding). The step search grows from trials
    // whose coarse samples of the gap lie near 0 without measuring them, and measures one
    // in full before it becomes a block (path_stepper.hpp, kGrowsOnCoarse): at θ = 85.4 rad
    // here such a trial's gap is 3e-4 of the target and its slide 1.5 times it. Blocks
    // taken on their coarse samples alone fail here (3 segments, slides up to 152 nm).
    const LensletArray eye(test::compound_eye_options(2.2));
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, 1.6));
    const double R = 0.2, pitch = 0.05, tolerance = 2e-4;
    const auto radial = [](const Eigen::Vector3d& p, double c) {
      return p.x() * std::cos(c) + p.y() * std::sin(c);
    };
    SpiralOptions o = spiral_options(1.6, pitch, tolerance, R);
    o.points.max_angle_step = 4 * std::numbers::pi / 180;
    std::vector<ContactPoint> chord_points, path_points;
    const std::vector<CutterLocation> chord = plan_with_nose(eye, base, o, &chord_points);
    // The same path to r = 0.9 mm (its points do not depend on where it ends).
    const double envelope = R + chord_points.front().stand_off;
    o.inner_radius = 0.9;
    o.points.rule = CutterPointRule::kEqualAngle;
    o.points.points_per_revolution = 20000;
    o.tool.nose_radius = envelope;
    REQUIRE(stand_off_for(o.points, o.tool, eye) == 0);
    const std::vector<CutterLocation> along = plan_with_nose(eye, base, o, &path_points);
    std::size_t j = 0;
    int over = 0, sampled = 0;
    double largest = 0;
    for (std::size_t k = 1; k < chord.size() && chord[k].contact.theta < along.back().contact.theta;
         ++k) {
      const double ta = chord[k - 1].contact.theta, tb = chord[k].contact.theta;
      const double xa = radial(chord[k - 1].nose_centre, ta), xb = radial(chord[k].nose_centre, tb);
      const double za = chord[k - 1].nose_centre.z(), zb = chord[k].nose_centre.z();
      const double reported = chord_points[k].chord_error - chord_points[k].stand_off;
      double slide = 0;
      while (j < along.size() && along[j].contact.theta <= ta) ++j;
      for (; j < along.size() && along[j].contact.theta < tb; ++j, ++sampled) {
        const double theta = along[j].contact.theta, t = (theta - ta) / (tb - ta);
        const double x = xa + t * (xb - xa), z = za + t * (zb - za);
        const double px = radial(along[j].nose_centre, theta), pz = along[j].nose_centre.z();
        const ContactPoint& p = path_points[j];
        const double slope =
            -(p.normal.x() * std::cos(theta) + p.normal.y() * std::sin(theta)) / p.normal.z();
        for (const double side : {-0.5, 0.5}) {
          const double rho = p.r + side * pitch;
          const auto lower_arc = [&](double cx, double cz) {
            return cz - std::sqrt(std::max(envelope * envelope - (rho - cx) * (rho - cx), 0.0));
          };
          slide = std::max(slide, (lower_arc(x, z) - lower_arc(px, pz)) / std::hypot(1.0, slope));
        }
      }
      largest = std::max(largest, slide);
      over += slide > 1.005 * reported + 1e-9;
    }
    MESSAGE(chord.size(), " blocks, ", sampled, " noses of the path, slide up to ", largest * 1e6,
            " nm, ", over, " segments over their error");
    CHECK(sampled > 250000);
    CHECK(largest > 0.3 * tolerance);  // the slide is there to be measured
    CHECK(over == 0);
  }

  TEST_CASE("a nose riding a rim at 10 nm a turn: its samples of rounding are not taken") {
    // The compound eye's central lenslet has a circular rim (r ≈ 0.45 mm) that a 0.2 mm nose
    // is held at; at 10 nm a turn and 100 equal steps a turn the turns follow it, and most
    // deviations about it are rounding (a radial step's square is 1e-14 mm and under). A sample
    // of rounding shows no shape, so no slopes' test could leave the samples between out:
    // the slide then took most of its 33 path states a segment, about 0.6 of the
    // evaluations of a plan that takes every sample. The slide's parts are smooth where
    // pruned (path_stepper.hpp, peak_may_lie_in), so samples within half of kPeakKnownTo
    // (1e-13 mm) of 0 about an interval leave it out: under half as many. Equal angles
    // place the same blocks either way, and each segment's error stays within 0.5 % or
    // 1e-11 mm of the one measured at every sample (the crease searches settle a piece's
    // top to 1e-9 mm, kSettled: on these rims a value of rounding may come out 2e-12 mm
    // apart between two samplings).
    const LensletArray eye(test::compound_eye_options(2.2));
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, 1.6));
    for (const double centre : {0.44, 0.45, 0.46}) {
      CAPTURE(centre);
      double per_point[2];
      std::vector<ContactPoint> plans[2];
      for (const bool every : {false, true}) {
        const test::CountingSurface counting(eye);
        SpiralOptions o = spiral_options(centre + 1e-4, 1e-5, 2e-4, 0.2);
        o.inner_radius = centre - 1e-4;
        o.points.rule = CutterPointRule::kEqualAngle;
        o.points.points_per_revolution = 100;
        o.take_every_sample = every;
        plan_with_nose(counting, base, o, &plans[every]);
        per_point[every] =
            static_cast<double>(counting.evaluations) / static_cast<double>(plans[every].size());
      }
      REQUIRE(same_blocks(plans[0], plans[1]));
      int held = 0, lower = 0;
      for (std::size_t k = 1; k < plans[0].size(); ++k) {
        held += plans[0][k].uncut_residual > 0;
        const double pruned = plans[0][k].chord_error - plans[0][k].stand_off;
        const double full = plans[1][k].chord_error - plans[1][k].stand_off;
        lower += pruned < 0.995 * full - 1e-11;
      }
      MESSAGE(centre, " mm: ", plans[0].size(), " points, ", held, " held, evaluations a point ",
              per_point[0], " pruned, ", per_point[1], " every sample");
      CHECK(held > 0);
      CHECK(lower == 0);
      CHECK(per_point[0] <= 0.5 * per_point[1]);
    }
  }

  TEST_CASE("equal angles with a 0.1 mm nose: a short hold inside an eighth whose ends are free") {
    // A hold about one grid interval long, inside an eighth whose end states are free,
    // can change flank mid-hold, and the slide jumps there: at r = 1.2 mm (100 steps a turn)
    // grid states 17 and 18 of a segment are held, 16 and 20 free, and the slide steps from
    // 1.492 to 1.518 µm between 17.50/32 and 17.55/32. Pruned on the held states at the
    // eighths' ends alone, 138 of these segments came out more than 0.5 % under the measure
    // at every sample (down to 0.989 of it), and 48 at r = 0.8 mm, 1000 a turn (down to
    // 0.975); over r = 0.3 to 1.5 mm and noses of 0.1 to 0.4 mm, 245 of 2.35 M (down to
    // 0.899). An eighth with free ends is now pruned only where its ends' touches are clear
    // of the creases (path_stepper.hpp, TouchesClear).
    const LensletArray eye(test::compound_eye_options(2.2));
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, 1.6));
    for (const auto& [centre, per_turn] : {std::pair{1.2, 100}, std::pair{0.8, 1000}}) {
      CAPTURE(centre);
      std::vector<ContactPoint> plans[2];
      for (const bool every : {false, true}) {
        SpiralOptions o = spiral_options(centre + 2e-4, 1e-5, 2e-4, 0.1);
        o.inner_radius = centre - 2e-4;
        o.points.rule = CutterPointRule::kEqualAngle;
        o.points.points_per_revolution = per_turn;
        o.take_every_sample = every;
        plan_with_nose(eye, base, o, &plans[every]);
      }
      REQUIRE(same_blocks(plans[0], plans[1]));
      int lower = 0;
      double lowest = 1;
      for (std::size_t k = 1; k < plans[0].size(); ++k) {
        const double pruned = plans[0][k].chord_error - plans[0][k].stand_off;
        const double full = plans[1][k].chord_error - plans[1][k].stand_off;
        lower += pruned < 0.995 * full - 1e-13;
        if (full > 1e-12) lowest = std::min(lowest, pruned / full);
      }
      MESSAGE(centre, " mm: ", plans[0].size(), " points, pruned/full down to ", lowest, ", ",
              lower, " lower by 0.5 %");
      CHECK(lower == 0);
    }
  }

  TEST_CASE("equal angles on lenslets: the pruned samples miss no segment's peak") {
    // Equal angles place no block where a hold begins or ends (the chord rule does), so at
    // 8° a step a segment may hold a whole hold, or a change of flank, between its
    // blocks, and the slide there can be a bump a few of its 32 samples wide. The planner
    // takes the slide's finer samples only where its peak may lie, and only in the eighths
    // of a segment over which the path's nose stays as it was, bounding each of its two
    // rises on its own (path_stepper.hpp, Pruning). With equal angles both plans have the
    // same blocks, so each segment's error can be set against the one measured at every
    // sample (take_every_sample): never lower by more than the 0.5 % the peak search
    // itself allows. Pruned in every eighth, held or not, the compound eye's slide misses
    // 6 segments' peaks (by up to 35 %); pruned as one function, not as its two rises,
    // the microlens array's misses one (by 1.1 %: the other rise overtook between two
    // samples). The gap is pruned as well, above the band's centre.
    // The pruned plan's contacts and cutter locations.
    std::vector<ContactPoint> contacts;
    std::vector<CutterLocation> cls;
    const auto compare = [&](const Surface& s, const BaseSurface& base, SpiralOptions o, double R) {
      o.points.rule = CutterPointRule::kEqualAngle;
      std::vector<ContactPoint> plans[2];
      for (const bool every : {false, true}) {
        o.take_every_sample = every;
        std::vector<CutterLocation> planned = plan_with_nose(s, base, o, &plans[every]);
        if (!every) cls = std::move(planned);
      }
      REQUIRE(same_blocks(plans[0], plans[1]));
      double lowest = 1e300;
      int lower = 0, held = 0;
      for (std::size_t k = 1; k < plans[0].size(); ++k) {
        held += plans[0][k].uncut_residual > 0;
        const double pruned = plans[0][k].chord_error - plans[0][k].stand_off;
        const double full = plans[1][k].chord_error - plans[1][k].stand_off;
        if (!(full > 1e-9)) continue;  // under a picometre: rounding
        lowest = std::min(lowest, pruned / full);
        lower += pruned < 0.995 * full;
      }
      MESSAGE("R ", R, ": ", plans[0].size(), " points, ", held, " held, pruned/full down to ",
              lowest, ", ", lower, " lower by 0.5 %");
      CHECK(held > 0);
      CHECK(lower == 0);
      contacts = std::move(plans[0]);
    };
    const LensletArray eye(test::compound_eye_options(2.2));
    SpiralOptions o = spiral_options(1.6, 0.02, 2e-4, 0.4);
    o.points.points_per_revolution = 45;
    const BaseSurface base = fit_base_least_squares(sample_aperture(eye, 0, 1.6));
    compare(eye, base, o, 0.4);
    // And the cut: what is left within the planner's own bound.
    const double bound = residual_bound(contacts);
    const double left = test::dense_spiral_residual(eye, cls, 0.4, 360, 0.1, 1.55, 0.0025);
    MESSAGE("left ", left * 1e6, " nm, bound ", bound * 1e6, " nm");
    CHECK(left > 0);
    CHECK(left <= bound);

    const LensletArray mla = microlens_plate(-5.0);
    SpiralOptions m = spiral_options(1.2, 0.02, 2e-4, 0.3);
    m.points.points_per_revolution = 45;
    compare(mla, BaseSurface::plane(1.5), m, 0.3);
  }

  TEST_CASE("microlens array on a plane, traditional spiral with a nose: no gouge at the rims") {
    const LensletArray mla = microlens_plate(-2.0);
    const double R = 0.1;
    SpiralOptions o = spiral_options(1.2, 0.04, 2e-4, R);
    PathSummary summary;
    const std::vector<CutterLocation> cls =
        plan_with_nose(mla, BaseSurface::plane(1.5), o, nullptr, &summary);
    CHECK(summary.jumps == 0);
    const test::DenseNoseFigures f = test::dense_nose_figures(mla, cls, R, 12, 240);
    MESSAGE("points ", cls.size(), ", deepest ", f.gouge * 1e6, " nm, chord ", f.worst * 1e6,
            " nm");
    CHECK(f.gouge <= 10e-6);
    CHECK(f.worst <= 2e-4 * 1.02);
  }

  TEST_CASE("a trough narrower than the nose: held on the lenslets either side, in closed form") {
    // Convex lenslets (R 0.3 mm, D 0.2 mm) at a 0.25 mm pitch on a plane: on θ = 0 the
    // lenslets about x = 0.5 and 0.75 leave a flat 0.05 mm wide between their rims at 0.6
    // and 0.65, and a 0.2 mm nose cannot reach it. Either hold alone (the flat and one
    // lenslet) put the nose into the other lenslet, 21 µm at a rim. The nose touches both
    // lenslets: by symmetry its centre is at x = 0.625, (0.3 + R) from each lens centre
    // (0.5 or 0.75, −√(0.3² − 0.1²)), and it touches at 0.5 + 0.3·0.125/0.5 = 0.575.
    const LensletArray mla = close_lenslets(1.0);
    const double R = 0.2, below = std::sqrt(0.09 - 0.01);
    const double centre_z = std::sqrt(0.25 - 0.125 * 0.125) - below;
    const double uncut = centre_z - std::sqrt(R * R - 0.025 * 0.025);  // over the flat at a rim
    const RadialLine line(0.0);
    for (const double rho : {0.6, 0.6 + 1e-9, 0.61, 0.625, 0.6297, 0.64, 0.65 - 1e-9, 0.65}) {
      CAPTURE(rho);
      double z, zx, zy;
      mla.sag_gradient(rho, 0, z, zx, zy);
      const NoseTouch t = nose_touch(mla, line, R, rho, z, zx);
      CHECK(t.held);
      CHECK(std::abs(t.centre_x - 0.625) < 1e-9);
      CHECK(std::abs(t.centre_z - centre_z) < 1e-9);
      CHECK(std::min(std::abs(t.rho - 0.575), std::abs(t.rho - 0.675)) < 1e-9);
      CHECK(std::abs(t.uncut - uncut) < 1e-9);
    }
  }

  TEST_CASE("lenslets closer than the nose is wide: no contact's nose overhangs the section") {
    // The same array under a 0.2 mm and a 0.3 mm nose, contacts every 0.37 µm of radius on
    // 24 radial lines: each nose against the section by brute force (4001 values across
    // it, then golden section about the highest). Before troughs were held on both sides
    // (and a hold that still overhung was replaced by another crease's), the deepest were
    // 21.6 µm; a search of 4 steps on a steep lenslet had also missed an overhang of
    // 0.25 µm well inside one.
    const LensletArray mla = close_lenslets(1.0);
    for (const double R : {0.2, 0.3}) {
      double deepest = -1;
      long held = 0, contacts = 0;
      for (int k = 0; k < 24; ++k) {
        const RadialLine line(0.0087 + k * 2 * std::numbers::pi / 24);
        for (double rho = 0.05; rho <= 0.8; rho += 3.7e-4) {
          double z, zx, zy;
          mla.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
          const NoseTouch t = nose_touch(mla, line, R, rho, z, zx * line.cos + zy * line.sin);
          ++contacts;
          held += t.held;
          const auto overlap = [&](double r) {
            double g, gx, gy;
            mla.sag_gradient(r * line.cos, r * line.sin, g, gx, gy);
            const double d = r - t.centre_x;
            return g - (t.centre_z - std::sqrt(std::max(R * R - d * d, 0.0)));
          };
          double best = -1, at = t.centre_x;
          for (int i = 0; i <= 4000; ++i) {
            const double r = t.centre_x + R * 0.999 * (i / 2000.0 - 1);
            if (std::abs(r) > 1.0) continue;
            const double o = overlap(r);
            if (o > best) best = o, at = r;
          }
          double a = at - R / 2000, b = at + R / 2000;  // golden section about the highest
          for (int i = 0; i < 60; ++i) {
            const double m1 = b - 0.618033988749895 * (b - a), m2 = a + 0.618033988749895 * (b - a);
            if (overlap(m1) > overlap(m2))
              b = m2;
            else
              a = m1;
          }
          if (std::abs(a) <= 1.0) best = std::max(best, overlap(0.5 * (a + b)));
          if (best > 1e-9 && deepest <= 1e-9)
            MESSAGE("first overhang ", best * 1e6, " nm: nose ", R, " θ ", line.theta, " ρ ", rho,
                    " held ", t.held, " centre ", t.centre_x, " ", t.centre_z, " at ", at);
          deepest = std::max(deepest, best);
        }
      }
      MESSAGE("nose ", R, " mm: ", contacts, " contacts, ", held, " held, deepest ", deepest * 1e6,
              " nm");
      CHECK(held > contacts / 10);
      CHECK(deepest <= 1e-9);
    }
  }

  TEST_CASE("steep domes closer than the nose is wide: the stand-off's nose overhangs no wall") {
    // Domes of radius 0.11 mm (walls at 65° where they meet the plane) on a 0.25 mm pitch,
    // D 0.2 mm, under a 0.2 mm nose placed with a 0.1 µm stand-off (the envelope of a
    // 0.2001 mm nose). The overhang of a dome behind the contact was searched from its near
    // rim over a piece bounded by its far rim, beyond the nose's reach: the first Newton
    // step left the arc's footprint and the search ended on the rim's value. A free nose
    // was placed 3 nm from a wall its envelope overhung by 122 nm (θ = 26.374141126 rad,
    // ρ = 0.979012125 mm, the chord rule stopping with "the path is not smooth here"); over
    // the sweep below the deepest envelope stood 47.3 µm into a wall, 276 of 2240 held.
    // Each placed envelope against the section by brute force (nose_brute_force.hpp).
    const LensletArray mla = close_lenslets(1.0, -0.11);
    const double R = 0.2, stand_off = 1e-4, lifted = R + stand_off;
    const auto worst_overhang = [&](const RadialLine& line, double rho, bool& held) {
      double z, zx, zy;
      mla.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const NoseTouch t =
          nose_touch(mla, line, R, rho, z, zx * line.cos + zy * line.sin, stand_off);
      held = t.held;
      return brute_overlap(mla, t.centre_x, t.centre_z, lifted, line.theta, 4000);
    };
    bool held = false;
    const double found = worst_overhang(RadialLine(26.374141126), 0.979012125, held);
    MESSAGE("the contact found: held ", held, ", overhang ", found * 1e6, " nm");
    CHECK(held);
    CHECK(found <= 1e-9);
    double deepest = -1;
    long held_count = 0, contacts = 0;
    for (int k = 0; k < 8; ++k) {
      const RadialLine line(26.374141126 + k * 2 * std::numbers::pi / 8);
      for (double rho = 0.70; rho <= 0.98; rho += 1e-3) {
        deepest = std::max(deepest, worst_overhang(line, rho, held));
        held_count += held;
        ++contacts;
      }
    }
    MESSAGE(contacts, " contacts, ", held_count, " held, deepest ", deepest * 1e6, " nm");
    CHECK(held_count > contacts / 10);
    CHECK(deepest <= 1e-9);
  }

  TEST_CASE(
      "lenslets closer than the nose is wide, chord-planned spiral: no gouge, the tolerance kept") {
    // The nose (0.2 mm) spans the 0.05 mm flats between lenslets (R 0.3 mm, D 0.2 mm):
    // its holds reach across troughs. This plan had stopped with "the path is not smooth
    // here" where a trough's touch changed lenslet (searched from a hint on the flat,
    // the overlap missed both touching lenslets by 0.24 µm).
    const LensletArray mla = close_lenslets(0.5);
    const double R = 0.2;
    SpiralOptions o = spiral_options(0.5, 0.02, 2e-4, R);
    PathSummary summary;
    const std::vector<CutterLocation> cls =
        plan_with_nose(mla, BaseSurface::plane(0.5), o, nullptr, &summary);
    const test::DenseNoseFigures f = test::dense_nose_figures(mla, cls, R, 12, 240);
    MESSAGE("points ", cls.size(), ", jumps ", summary.jumps, ", deepest ", f.gouge * 1e6,
            " nm, chord ", f.worst * 1e6, " nm");
    CHECK(summary.jumps == 0);
    CHECK(f.gouge <= 10e-6);
    CHECK(f.worst <= 2e-4 * 1.02);
  }

  TEST_CASE("a NURBS with a C⁰ seam, spiral with a nose: the seam found from its knots, no gouge") {
    // A V-groove 6.4° deep each side across x = 0.5 (a triple knot of a cubic): the
    // planner is told of it by the knots alone (NurbsHeightField::section_creases).
    const double m = 0.1115, R = 0.2;
    const NurbsHeightField groove(test::v_groove(0.5, m));
    SpiralOptions o = spiral_options(1.2, 0.05, 2e-4, R);
    std::vector<ContactPoint> contacts;
    PathSummary summary;
    const std::vector<CutterLocation> cls =
        plan_with_nose(groove, BaseSurface::plane(1.2), o, &contacts, &summary);
    const double worst_uncut = check_held_spiral(groove, cls, contacts, summary, R, 2e-4);
    // Across the groove (θ = 0, π) the section's half-angle is atan m, and the nose, lifted
    // ε/2, leaves (R + ε/2)/cos(atan m) − R at the bottom; other sections cross it at a
    // shallower angle and leave less.
    const double lifted = R + 0.5 * o.points.tolerance;
    const double closed_form = lifted * std::sqrt(1 + m * m) - R;
    CHECK(worst_uncut <= closed_form * (1 + 1e-6));
    CHECK(worst_uncut >= 0.95 * closed_form);
  }

  TEST_CASE("sinusoidal ring as a spiral through its cone point: no gouge at the apex") {
    // z = A sin(ωr): the section through the axis folds at r = 0 with slope ±Aω.
    const double A = 0.005, w = 2 * std::numbers::pi / 2.5;
    const SinusoidalRing ring(A, w, 0.0);
    const double R = 0.5;
    SpiralOptions o = spiral_options(1.0, 0.02, 1e-4, R);
    std::vector<ContactPoint> contacts;
    const std::vector<CutterLocation> cls =
        plan_with_nose(ring, BaseSurface::plane(1.0), o, &contacts);
    // The last contact is held where the nose, standing off ε/2, touches both sides of the
    // cone: its centre on the axis (by symmetry) at the height where a circle of radius
    // R + ε/2 about it just clears the section, max over ρ of f(ρ) + √((R + ε/2)² − ρ²)
    // (brute force), close to (R + ε/2)/cos ψ, ψ = atan(Aω) (the sine bends a little over
    // the 6 µm to the touch); the residual is that height less the real nose's R.
    const double psi = std::atan(A * w), lifted = R + 0.5 * o.points.tolerance;
    const double held_z = brute_overlap(ring, 0.0, 0.0, lifted);  // = max f(ρ) + √(R'² − ρ²)
    CHECK(held_z == doctest::Approx(lifted / std::cos(psi)).epsilon(1e-7));
    REQUIRE(contacts.back().uncut_residual > 0);
    CHECK(std::abs(cls.back().nose_centre.x()) < 1e-9);
    CHECK(std::abs(cls.back().nose_centre.z() - held_z) < 1e-9);
    CHECK(std::abs(contacts.back().uncut_residual - (held_z - R)) < 1e-9);
    const test::DenseNoseFigures f = test::dense_nose_figures(ring, cls, R, 20, 400);
    MESSAGE("points ", cls.size(), ", deepest ", f.gouge * 1e6, " nm, chord ", f.worst * 1e6,
            " nm");
    CHECK(f.gouge <= 10e-6);
  }

  TEST_CASE("coma through the centre: the nose centre crosses the axis, and the nose stays above") {
    // Coma (Noll 8, 50 µm on a 2 mm radius) on a sphere: a slope of 2·√8·A/R_n = 0.14 at
    // the axis, so the section through the axis is tilted there and the centre of a
    // 0.3 mm nose sits up to R·0.14 = 42 µm across the axis on the last turn (half a pitch,
    // 25 µm, from it at most where the slope points outward).
    std::vector<double> coefficients(8, 0.0);
    coefficients[7] = 0.05;
    const Zernike coma(1 / 30.0, 0, {}, 2.0, coefficients);
    const double R = 0.3;
    SpiralOptions o = spiral_options(2.0, 0.05, 2e-4, R);
    const std::vector<CutterLocation> cls = plan_with_nose(coma, BaseSurface::plane(2.0), o);
    double least_x = 1e300;
    for (const CutterLocation& cl : cls) {
      const double t = cl.contact.theta;
      least_x =
          std::min(least_x, cl.nose_centre.x() * std::cos(t) + cl.nose_centre.y() * std::sin(t));
    }
    CHECK(least_x < -0.01);  // the centre passes through the axis
    const test::DenseNoseFigures f = test::dense_nose_figures(coma, cls, R, 12, 240);
    MESSAGE("points ", cls.size(), ", deepest ", f.gouge * 1e6, " nm, chord ", f.worst * 1e6,
            " nm");
    CHECK(f.gouge <= 10e-6);
    CHECK(f.worst <= 2e-4 * 1.02);
  }

  TEST_CASE(
      "a nose over more creases than a list holds: measured where whole, else in the design") {
    // Domes 18 µm across at a 20 µm pitch (radius 0.6 mm) under a 0.5 mm nose: along the
    // row θ = 0 about a hundred rims lie under it, within the 256 a list holds, and the
    // overlap is brute force's. At a 6 µm pitch about 330 do: no overlap is measured from a
    // list that leaves some out, and the nose is taken to be in the design (+∞), so that
    // no chord is measured clear there. The placement there is the contact's own offset.
    const double R = 0.5;
    for (const double pitch : {0.02, 0.006}) {
      CAPTURE(pitch);
      const LensletArray domes({.lens_radius = -0.6,
                                .lens_diameter = 0.9 * pitch,
                                .pitch = pitch,
                                .pattern = LensletArrayOptions::Pattern::kSquare,
                                .extent = 1.0});
      std::array<double, 512> all;
      const int under = domes.section_creases(RadialLine(0.0), -0.499, 0.499, all);
      const double x = 0.0013, z = domes.sag(x, 0) + R;
      const NoseOverlap o = nose_overlap(domes, RadialLine(0.0), x, z, R, x);
      if (pitch > 0.01) {
        REQUIRE(under > 32);
        REQUIRE(under <= SectionCreases::kCapacity);
        CHECK(std::abs(o.height - brute_overlap(domes, x, z, R, 0.0, 200000)) < 1e-10);
      } else {
        REQUIRE(under > SectionCreases::kCapacity);
        CHECK(o.height == std::numeric_limits<double>::infinity());
        double g, gx, gy;
        domes.sag_gradient(x, 0, g, gx, gy);
        const NoseTouch t = nose_touch(domes, RadialLine(0.0), R, x, g, gx);
        CHECK(std::abs(t.centre_x - (x - R * gx / std::sqrt(1 + gx * gx))) < 1e-15);
        CHECK(!t.held);
      }
    }
  }

  TEST_CASE("a nose wider than the lenslets rests on the crests either side of its gap") {
    // Domes of radius 1 mm, 0.18 mm across at a 0.2 mm pitch, under a 3 mm nose, on the
    // section θ = 0.711742 (a spiral's, where the chord rule had stopped): the contacts
    // between the domes' crests at 0.6032 and 0.8149 lie in one gap of the envelope, and
    // the nose rests on both crests, one centre for all, no point of it in the design
    // (brute force). The hold at a valley between two domes reached 84 nm into a third's
    // crest, and was kept: it overhung one flank alone, and was not checked against the rest.
    const LensletArray domes({.lens_radius = -1.0,
                              .lens_diameter = 0.18,
                              .pitch = 0.2,
                              .pattern = LensletArrayOptions::Pattern::kSquare,
                              .extent = 1.0});
    const double R = 3.0, stand_off = 1e-4, placed = R + stand_off;
    const RadialLine line(0.711742);
    double first_x = std::numeric_limits<double>::quiet_NaN();
    for (double rho = 0.70; rho <= 0.74; rho += 0.0025) {
      CAPTURE(rho);
      double z, zx, zy;
      domes.sag_gradient(rho * line.cos, rho * line.sin, z, zx, zy);
      const NoseTouch t =
          nose_touch(domes, line, R, rho, z, zx * line.cos + zy * line.sin, stand_off);
      CHECK(std::abs(brute_overlap(domes, t.centre_x, t.centre_z, placed, line.theta, 400000)) <
            1e-9);
      CHECK(t.held);
      if (std::isnan(first_x)) first_x = t.centre_x;
      CHECK(std::abs(t.centre_x - first_x) < 1e-9);
    }
  }
}

}  // namespace freeturn
