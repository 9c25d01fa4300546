#include "freeturn/io/surface_samples.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
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
                                        double outer_radius, int grid_n, const std::string& path,
                                        double max_mb) {
  if (grid_n < 2) throw InputError(path, "the sample grid needs at least 2 points per side");
  const double max_bytes = max_mb * 1048576.0;
  const auto too_large = [&](const std::string& how) {
    return InputError("limits.max_file_mb",
                      "the samples of a " + std::to_string(grid_n) + " × " +
                          std::to_string(grid_n) + " grid " + how +
                          " limits.max_file_mb = " + significant_text(max_mb, 6) +
                          " MB; give a coarser grid (nothing was written)");
  };
  // The rows inside the ring, from its share of the square less a row and column of
  // boundary, each at least "0,0,0,0,0,1\n".
  const double share = std::numbers::pi *
                       (outer_radius * outer_radius - inner_radius * inner_radius) /
                       (4 * outer_radius * outer_radius);
  const double fewest_rows = std::max(0.0, share * grid_n * grid_n - 4.0 * grid_n);
  if (fewest_rows * 12 > max_bytes)
    throw too_large("would take at least " + significant_text(fewest_rows * 12 / 1048576.0, 4) +
                    " MB, over");
  AtomicFile file(path);
  std::size_t written = 0;
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
        written += buffer.size();
        if (static_cast<double>(written) > max_bytes) throw too_large("grow past");
        file.write(buffer);
        buffer.clear();
      }
    }
  }
  if (static_cast<double>(written + buffer.size()) > max_bytes) throw too_large("grow past");
  file.write(buffer);
  file.commit();
  return summary;
}

}  // namespace freeturn
