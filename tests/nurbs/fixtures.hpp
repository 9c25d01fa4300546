#pragma once
// NURBS shapes with known closed forms, shared by the nurbs tests.

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "freeturn/nurbs/curve.hpp"
#include "freeturn/nurbs/surface.hpp"

namespace freeturn::test {

using nurbs::NurbsCurve;
using nurbs::NurbsSurface;
using nurbs::Vector3d;

inline const double kHalfRoot2 = std::sqrt(0.5);

// Quarter circle of radius r in the xy plane, from (r, 0) to (0, r): degree 2, weights
// 1, √2/2, 1 (The NURBS Book, Ex. 7.1).
inline NurbsCurve quarter_circle(double r) {
  return NurbsCurve(2, {0, 0, 0, 1, 1, 1}, {{r, 0, 0}, {r, r, 0}, {0, r, 0}}, {1, kHalfRoot2, 1});
}

// Full circle of radius r: nine points on a square, degree 2 (The NURBS Book, Fig. 7.16).
inline NurbsCurve full_circle(double r) {
  const double w = kHalfRoot2;
  return NurbsCurve(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1},
                    {{r, 0, 0},
                     {r, r, 0},
                     {0, r, 0},
                     {-r, r, 0},
                     {-r, 0, 0},
                     {-r, -r, 0},
                     {0, -r, 0},
                     {r, -r, 0},
                     {r, 0, 0}},
                    {1, w, 1, w, 1, w, 1, w, 1});
}

// An octant of a sphere of radius r about the origin: the quarter circle from (r,0,0)
// over (r,0,r) to the pole (0,0,r), revolved 90° about z. u runs along the meridian (the
// edge u = 1 is the pole), v around z.
inline NurbsSurface sphere_octant(double r) {
  const double w = kHalfRoot2;
  const double prof_x[3] = {r, r, 0}, prof_z[3] = {0, r, r}, prof_w[3] = {1, w, 1};
  const double cx[3] = {1, 1, 0}, cy[3] = {0, 1, 1}, cw[3] = {1, w, 1};
  std::vector<Vector3d> pts;
  std::vector<double> wts;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      pts.emplace_back(prof_x[i] * cx[j], prof_x[i] * cy[j], prof_z[i]);
      wts.push_back(prof_w[i] * cw[j]);
    }
  return NurbsSurface(2, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, pts, wts);
}

// A full sphere band about z (closed in v): the profile arc from 45° below to 45° above
// the equator, revolved 360°. Radius r.
inline NurbsSurface closed_sphere_band(double r) {
  const double w = kHalfRoot2;
  const double s = r * kHalfRoot2;
  // Profile: 90° arc from (s, -s) to (s, s) in (x, z), middle point (r·√2, 0) weight cos45.
  const double prof_x[3] = {s, 2 * s, s}, prof_z[3] = {-s, 0, s}, prof_w[3] = {1, w, 1};
  const double cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  const double cw[9] = {1, w, 1, w, 1, w, 1, w, 1};
  std::vector<Vector3d> pts;
  std::vector<double> wts;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 9; ++j) {
      pts.emplace_back(prof_x[i] * cx[j], prof_x[i] * cy[j], prof_z[i]);
      wts.push_back(prof_w[i] * cw[j]);
    }
  return NurbsSurface(2, 2, {0, 0, 0, 1, 1, 1},
                      {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, pts, wts);
}

// A rational bicubic 20 × 20 freeform with a pole: control points on a polar fan
// (radius ρ_i = 10·i/19 mm, angle φ_j over 270°), so the whole edge u = 0 collapses to
// the centre; heights are smooth bumps of ±0.5 mm plus random ±0.05 mm; weights in
// [0.8, 1.2]. Clamped uniform knots on [0, 1].
inline NurbsSurface freeform_with_pole(unsigned seed = 42) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), weight(0.8, 1.2);
  const int n = 20;
  std::vector<Vector3d> pts;
  std::vector<double> wts;
  for (int i = 0; i < n; ++i) {
    const double rho = 10.0 * i / (n - 1);
    for (int j = 0; j < n; ++j) {
      const double phi = 1.5 * M_PI * j / (n - 1);
      const double x = rho * std::cos(phi), y = rho * std::sin(phi);
      double z = 0.5 * std::sin(0.6 * x) * std::cos(0.4 * y) + 0.01 * rho * rho;
      if (i > 0) z += jitter(rng);
      pts.emplace_back(x, y, i == 0 ? 0.0 : z);
      wts.push_back(i == 0 ? 1.0 : weight(rng));
    }
  }
  std::vector<double> knots(n + 4);
  for (int k = 0; k < n + 4; ++k) knots[k] = std::clamp((k - 3) / double(n - 3), 0.0, 1.0);
  return NurbsSurface(3, 3, knots, knots, pts, wts);
}

// A V-groove along the line x = x_k: z = m·|x − x_k| for x in [x_k − 2, x_k + 2], y in
// [−2, 2]. Cubic in u with a triple knot at u = 1/2 (two Bézier pieces sharing the
// control point on the groove), linear in v; each piece reproduces the linear data at its
// Greville abscissae, so the sag is exact. m > 0 is a concave crease seen from the tool,
// with the angle 2·atan(m) in the section across it. `skewed` spaces the control points
// unevenly in x (x_i + 0.3 sin 2πg_i, still monotone, the groove's point kept): x is then
// no affine function of u, but z stays m·|x − x_k| exactly (an affine map of a Bézier
// piece's points maps the piece).
inline NurbsSurface v_groove(double x_k, double m, bool skewed = false) {
  const double greville[7] = {0, 1.0 / 6, 1.0 / 3, 0.5, 2.0 / 3, 5.0 / 6, 1};
  std::vector<Vector3d> points;
  for (const double g : greville)
    for (const double y : {-2.0, 2.0}) {
      const double x = x_k - 2 + 4 * g + (skewed ? 0.3 * std::sin(2 * std::numbers::pi * g) : 0.0);
      points.emplace_back(x, y, m * std::abs(x - x_k));
    }
  return NurbsSurface(3, 1, {0, 0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1, 1}, {0, 0, 1, 1}, points);
}

}  // namespace freeturn::test
