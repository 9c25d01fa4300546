#include "freeturn/verify/residual_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>

#include "freeturn/core/number_text.hpp"
#include "freeturn/io/atomic_file.hpp"

namespace freeturn {

ResidualHeatMap polar_heat_map(int rings, int columns, double inner, double radial_step,
                               const std::function<double(std::size_t)>& value, int size) {
  ResidualHeatMap map;
  map.size = size;
  const double outer = inner + (rings - 1) * radial_step;
  map.half_width = outer;
  const double pixel = 2 * outer / size;
  map.mean.assign(static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                  std::numeric_limits<double>::quiet_NaN());
  map.low = std::numeric_limits<double>::infinity();
  map.high = -map.low;
  for (int py = 0; py < size; ++py)
    for (int px = 0; px < size; ++px) {
      const double x = -outer + (px + 0.5) * pixel, y = outer - (py + 0.5) * pixel;
      const double rad = std::hypot(x, y);
      if (rad < inner - 0.5 * radial_step || rad > outer + 0.5 * radial_step) continue;
      double phi = std::atan2(y, x);
      if (phi < 0) phi += 2 * std::numbers::pi;
      const long column = std::lround(phi / (2 * std::numbers::pi) * columns) % columns;
      const int i0 =
          std::max(0, static_cast<int>(std::ceil((rad - 0.5 * pixel - inner) / radial_step)));
      const int i1 = std::min(
          rings - 1, static_cast<int>(std::floor((rad + 0.5 * pixel - inner) / radial_step)));
      double sum = 0;
      long count = 0;
      for (int i = i0; i <= i1; ++i) {
        const double e = value(static_cast<std::size_t>(i) * static_cast<std::size_t>(columns) +
                               static_cast<std::size_t>(column));
        if (std::isnan(e)) continue;
        sum += e;
        ++count;
      }
      if (count == 0) continue;
      const double mean = sum / static_cast<double>(count);
      map.mean[static_cast<std::size_t>(py) * static_cast<std::size_t>(size) +
               static_cast<std::size_t>(px)] = mean;
      map.low = std::min(map.low, mean);
      map.high = std::max(map.high, mean);
    }
  if (map.low > map.high) map.low = map.high = 0;
  return map;
}

ResidualHeatMap residual_heat_map(const SimulationResult& r, double inner, int size) {
  return polar_heat_map(r.rings, r.columns, inner, r.radial_step,
                        [&](std::size_t k) { return r.residual[k]; }, size);
}

void write_residual_csv(const SimulationResult& r, double inner, AtomicFile& f) {
  f.write("r_mm,phi_deg,residual_nm\n");
  std::string line;
  for (int i = 0; i < r.rings; ++i)
    for (int j = 0; j < r.columns; ++j) {
      const double e =
          r.residual[static_cast<std::size_t>(i) * static_cast<std::size_t>(r.columns) +
                     static_cast<std::size_t>(j)];
      line = significant_text(inner + i * r.radial_step, 9) + "," +
             significant_text(360.0 * j / r.columns, 9) + "," +
             (std::isnan(e) ? std::string() : fixed_text(e * 1e6, 6)) + "\n";
      f.write(line);
    }
}

void write_residual_ply(const SimulationResult& r, const Surface& design, double inner,
                        AtomicFile& f) {
  const int ring_step = std::max(1, r.rings / 200), column_step = std::max(1, r.columns / 360);
  const int rings = (r.rings - 1) / ring_step + 1, columns = r.columns / column_step;
  const double scale = std::max({std::abs(r.max), std::abs(r.min), 1e-12});
  const long faces = static_cast<long>(rings - 1) * columns * 2;
  f.write(
      "ply\nformat ascii 1.0\ncomment freeturn simulated residual: red above the design, blue "
      "below (mm)\n");
  char line[400];
  int n =
      std::snprintf(line, sizeof line,
                    "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                    "element face %ld\nproperty list uchar int vertex_indices\nend_header\n",
                    rings * columns, faces);
  f.write(std::string_view(line, static_cast<std::size_t>(n)));
  for (int a = 0; a < rings; ++a)
    for (int b = 0; b < columns; ++b) {
      const int i = a * ring_step, j = b * column_step;
      const double rad = inner + i * r.radial_step, phi = 2 * std::numbers::pi * j / r.columns;
      const double x = rad * std::cos(phi), y = rad * std::sin(phi);
      double e = r.residual[static_cast<std::size_t>(i) * static_cast<std::size_t>(r.columns) +
                            static_cast<std::size_t>(j)];
      if (std::isnan(e)) e = 0;
      const double t = std::clamp(e / scale, -1.0, 1.0);
      const int red = t < 0 ? static_cast<int>(255 * (1 + t)) : 255;
      const int blue = t > 0 ? static_cast<int>(255 * (1 - t)) : 255;
      const int green = static_cast<int>(255 * (1 - std::abs(t)));
      f.write(significant_text(x, 9) + " " + significant_text(y, 9) + " " +
              significant_text(design.sag(x, y), 9) + " " + std::to_string(red) + " " +
              std::to_string(green) + " " + std::to_string(blue) + "\n");
    }
  for (int a = 0; a + 1 < rings; ++a)
    for (int b = 0; b < columns; ++b) {
      const int v00 = a * columns + b, v01 = a * columns + (b + 1) % columns;
      const int v10 = v00 + columns, v11 = v01 + columns;
      n = std::snprintf(line, sizeof line, "3 %d %d %d\n3 %d %d %d\n", v00, v10, v11, v00, v11,
                        v01);
      f.write(std::string_view(line, static_cast<std::size_t>(n)));
    }
}

}  // namespace freeturn
