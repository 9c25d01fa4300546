#include "freeturn/io/surface_samples.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "freeturn/core/error.hpp"
#include "freeturn/io/atomic_file.hpp"

namespace freeturn {
namespace {

// Shortest round-trip decimal form (no iostreams, no locale).
void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace

SampleSummary write_surface_samples_csv(const Surface& surface, double inner_radius,
                                        double outer_radius, int grid_n, const std::string& path) {
  if (grid_n < 2) throw InputError(path, "the sample grid needs at least 2 points per side");
  AtomicFile file(path);
  std::string buffer = "x,y,z,nx,ny,nz\n";
  SampleSummary summary;
  summary.z_min = INFINITY;
  summary.z_max = -INFINITY;
  const double step = 2.0 * outer_radius / (grid_n - 1);
  for (int i = 0; i < grid_n; ++i) {
    const double y = -outer_radius + i * step;
    for (int j = 0; j < grid_n; ++j) {
      const double x = -outer_radius + j * step;
      const double r = std::hypot(x, y);
      if (r > outer_radius * (1 + 1e-12) || r < inner_radius) continue;
      double z, zx, zy;
      surface.sag_gradient(x, y, z, zx, zy);
      const double len = std::sqrt(1.0 + zx * zx + zy * zy);
      const double values[6] = {x, y, z, -zx / len, -zy / len, 1.0 / len};
      for (int k = 0; k < 6; ++k) {
        append_number(buffer, values[k]);
        buffer.push_back(k == 5 ? '\n' : ',');
      }
      summary.points++;
      summary.z_min = std::min(summary.z_min, z);
      summary.z_max = std::max(summary.z_max, z);
      summary.max_slope = std::max(summary.max_slope, std::acos(1.0 / len));
      if (buffer.size() > (1u << 20)) {
        file.write(buffer);
        buffer.clear();
      }
    }
  }
  file.write(buffer);
  file.commit();
  return summary;
}

}  // namespace freeturn
