#include "freeturn/surface/section_curvature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace freeturn {

namespace {

// The curvature at (x, y) of the design's section along the direction of `line`.
double section_curvature_at(const Surface& design, double x, double y, const RadialLine& line) {
  const HeightDerivatives h = design.height_derivatives(x, y);
  const double slope = h.zx * line.cos + h.zy * line.sin;
  const double bend =
      (h.zxx * line.cos + 2 * h.zxy * line.sin) * line.cos + h.zyy * line.sin * line.sin;
  const double stretch = 1 + slope * slope;
  return bend / (stretch * std::sqrt(stretch));
}

}  // namespace

double radial_section_curvature(const Surface& design, const RadialLine& line, double rho) {
  return section_curvature_at(design, rho * line.cos, rho * line.sin, line);
}

double line_section_curvature(const Surface& design, double x0, double y0, const RadialLine& line,
                              double rho) {
  return section_curvature_at(design, x0 + rho * line.cos, y0 + rho * line.sin, line);
}

double largest_section_curvature(const Surface& design, double inner_radius, double outer_radius,
                                 int radial, int angular) {
  double largest = -std::numeric_limits<double>::infinity(), change = 0;
  const int circles = std::max(radial, 2), lines = std::max(angular, 1);
  // One circle of samples at a time, with the one before it: the neighbours are the next
  // sample on the circle and the same line's on the last circle.
  std::vector<double> last(static_cast<std::size_t>(lines)), here(last.size());
  std::vector<RadialLine> line_at;
  for (int j = 0; j < lines; ++j) line_at.emplace_back(2 * std::numbers::pi * j / lines);
  const auto neighbours = [&](double a, double b) {
    if (std::isfinite(a) && std::isfinite(b)) change = std::max(change, std::abs(a - b));
  };
  for (int i = 0; i < circles; ++i) {
    const double rho = inner_radius + (outer_radius - inner_radius) * i / (circles - 1);
    for (std::size_t j = 0; j < here.size(); ++j) {
      here[j] = radial_section_curvature(design, line_at[j], rho);
      if (std::isfinite(here[j])) largest = std::max(largest, here[j]);
      if (i > 0) neighbours(here[j], last[j]);
      if (j > 0) neighbours(here[j], here[j - 1]);
    }
    neighbours(here.front(), here.back());
    std::swap(here, last);
  }
  return largest + change;
}

}  // namespace freeturn
