#pragma once
// The papers' test parts and classic freeform test pieces (shared/notes/optical-surfaces.md).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "freeturn/surface/jet_surface.hpp"

namespace freeturn {

// Sinusoidal ring (paper 001): z = A sin(ω r) + d. A surface of revolution whose profile
// is a sine in r; at the vertex it has a cone of slope A·ω (the gradient there is
// reported as 0, its average over directions).
class SinusoidalRing final : public JetSurface<SinusoidalRing> {
 public:
  SinusoidalRing(double amplitude, double angular_frequency, double offset)
      : a_(amplitude), w_(angular_frequency), d_(offset) {}
  const char* type() const override { return "sinusoidal_ring"; }
  bool has_creases() const override { return a_ * w_ != 0; }  // the cone at the vertex

  // Along a line just off the vertex the ring bends z'(r)·d²/r³ (d the line's distance from
  // the axis), without bound: max_bend keeps the default. A radial section is the profile
  // z(|ρ|), creased at the vertex (section_creases), and bends −Aω² sin(ω|ρ|) ≤ |A|ω².
  double max_section_bend(double radius) const override {
    if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
    return std::abs(a_) * w_ * w_;
  }

  template <typename T>
  T sag(const T& x, const T& y) const {
    const T r2 = x * x + y * y;
    if (value_of(r2) == 0) return T(d_);
    return a_ * sin(w_ * sqrt(r2)) + d_;
  }

  // The profile z(r) and its derivatives, for turning in X-Z.
  double profile(double r) const { return a_ * std::sin(w_ * r) + d_; }

 private:
  static double value_of(double v) { return v; }
  template <int N>
  static double value_of(const Jet<N>& j) {
    return j.v;
  }
  double a_, w_, d_;
};

// Sinusoidal grid: z = A sin(2πx/λx) sin(2πy/λy) (a common STS/FTS benchmark).
class SinusoidalGrid final : public JetSurface<SinusoidalGrid> {
 public:
  SinusoidalGrid(double amplitude, double wavelength_x, double wavelength_y)
      : a_(amplitude),
        kx_(2 * std::numbers::pi / wavelength_x),
        ky_(2 * std::numbers::pi / wavelength_y) {}
  const char* type() const override { return "sinusoidal_grid"; }

  // Along a unit direction (c, s) the second derivative is
  //   −A(kx²c² + ky²s²)·sin(kx x) sin(ky y) + 2A kx ky c s·cos(kx x) cos(ky y),
  // and |sin sin| + |cos cos| ≤ 1 (Cauchy–Schwarz), so it is at most |A| times the larger of
  // kx²c² + ky²s² and kx ky|2cs|, both ≤ max(kx, ky)²; reached at a crest or a trough.
  double max_bend(double) const override { return std::abs(a_) * std::max(kx_ * kx_, ky_ * ky_); }

  template <typename T>
  T sag(const T& x, const T& y) const {
    return a_ * (sin(kx_ * x) * sin(ky_ * y));
  }

 private:
  double a_, kx_, ky_;
};

// Alvarez / cubic phase plate: z = A (x y² + x³/3) + D x.
class Alvarez final : public JetSurface<Alvarez> {
 public:
  Alvarez(double a, double d) : a_(a), d_(d) {}
  const char* type() const override { return "alvarez"; }

  // The Hessian is 2A[[x, y], [y, x]], of eigenvalues 2A x ± 2|A y|: the larger is at most
  // 2|A|(|x| + |y|) ≤ 2√2|A|·r, reached on the disc's rim at 45° to the axes.
  double max_bend(double radius) const override {
    if (!(radius >= 0) || !std::isfinite(radius)) return std::numeric_limits<double>::infinity();
    return 2 * std::numbers::sqrt2 * std::abs(a_) * radius;
  }

  template <typename T>
  T sag(const T& x, const T& y) const {
    return a_ * (x * y * y + x * x * x * (1.0 / 3.0)) + d_ * x;
  }

 private:
  double a_, d_;
};

}  // namespace freeturn
