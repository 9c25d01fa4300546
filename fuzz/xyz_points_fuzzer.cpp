// Surface data files (io/xyz_points through job/surface_data_yaml): a height grid to
// interpolate or fit, or a scattered point cloud to fit, read from a file of x y z lines.
// The first byte picks which, the rest is the file. Any bytes either give a surface that
// evaluates or raise InputError; nothing else escapes, crashes, hangs or allocates
// without bound. The YAML around the file is fixed, so only the data varies.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>

#include "freeturn/core/error.hpp"
#include "freeturn/job/surface_yaml.hpp"
#include "fuzz_input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string& path = freeturn::fuzz::write_scratch(data + 1, size - 1, ".xyz");
  const std::string name = std::filesystem::path(path).filename().string();
  static const char* const kSurfaces[] = {
      "{type: height_grid, file: F}",
      "{type: height_grid, file: F, degree: 1}",
      "{type: height_grid, file: F, fit: least_squares, control_points: [4, 4], smoothing: 1e-6}",
      "{type: point_cloud, file: F, control_points: [4, 4]}",
      "{type: point_cloud, file: F, control_points: [5, 4], degree: 2}",
  };
  std::string text = kSurfaces[data[0] % 5];
  text.replace(text.find('F'), 1, name);
  // The job's own path only locates the data file, which sits beside it.
  const std::string job = (std::filesystem::path(path).parent_path() / "job.yaml").string();
  try {
    const auto surface = freeturn::surface_from_yaml(YAML::Load(text), job, 1.0);
    (void)surface->sag(0.5, 0.25);
  } catch (const freeturn::InputError&) {
  }
  return 0;
}
