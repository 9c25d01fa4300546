#include "compensation_yaml.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include "freeturn/core/number_text.hpp"
#include "freeturn/io/measurement_file.hpp"
#include "freeturn/surface/corrected_surface.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"
#include "freeturn/surface/polynomial_height.hpp"

namespace freeturn::detail {
namespace {

// The scale to mm of the unit under `key` (or `fallback`).
double unit_scale(MapReader& map, const std::string& key, const std::string& fallback) {
  const std::string unit = map.has(key) ? map.text(key) : fallback;
  double scale = 1;
  if (!length_unit_scale(unit, scale))
    map.fail(key, "compensation." + key + " must be mm, um, nm or m, not '" + unit + "'");
  return scale;
}

MeasuredPart read_part(const YAML::Node& node, const std::string& job_file, const Surface& design,
                       const Aperture& aperture) {
  MapReader map(node, job_file, "compensation");
  MeasuredPart part;
  part.file = map.text("measured");
  const std::string path =
      (std::filesystem::path(job_file).parent_path() / part.file).lexically_normal().string();
  part.format = map.has("format") ? map.text("format") : "xyz";
  MeasurementFileOptions read;
  if (part.format == "zygo_xyz") read.format = MeasurementFormat::kZygoXyz;
  else if (part.format == "xyz") read.format = MeasurementFormat::kXyz;
  else if (part.format == "csv") read.format = MeasurementFormat::kCsv;
  else if (part.format == "grid") read.format = MeasurementFormat::kGrid;
  else if (part.format == "profile") read.format = MeasurementFormat::kProfile;
  else
    map.fail("format", "compensation.format must be zygo_xyz, xyz, csv, grid or profile, not '" +
                           part.format + "'");
  read.lateral_scale = unit_scale(map, "lateral_unit", "mm");
  read.height_scale = unit_scale(map, "height_unit", part.format == "zygo_xyz" ? "um" : "mm");
  part.gain = map.in_range("gain", 1.0, 0.0, 1.5, true, "");
  // Where the design's axis is in the measurement's own x, y (mm, after lateral_unit): an
  // instrument counts pixels from a corner. The registration starts from there.
  double origin_x = 0, origin_y = 0;
  if (map.has("origin")) {
    const YAML::Node origin = map.child("origin");
    if (!origin.IsSequence() || origin.size() != 2)
      map.fail("origin", "compensation.origin is [x, y] in mm: where the design's axis is in the measurement");
    double* const xy[2] = {&origin_x, &origin_y};
    for (std::size_t k = 0; k < 2; ++k)
      if (!origin[k].IsScalar() || !parse_finite(origin[k].Scalar(), *xy[k]))
        throw InputError(location_of(origin[k], job_file),
                         "compensation.origin holds two finite numbers (mm)");
  }
  RegistrationOptions o;
  o.profile = read.format == MeasurementFormat::kProfile;
  if (map.has("register")) {
    o.piston = o.tilt = o.decentre = o.clocking = false;
    const YAML::Node list = map.child("register");
    if (!list.IsSequence())
      map.fail("register", "compensation.register is a list of piston, tilt, decentre, clocking");
    std::set<std::string> seen;
    for (const YAML::Node& item : list) {
      const std::string name = item.IsScalar() ? item.Scalar() : "";
      const SourceLocation at = location_of(item, job_file);
      if (!seen.insert(name).second) throw InputError(at, "'" + name + "' is listed twice");
      if (name == "piston") o.piston = true;
      else if (name == "tilt") o.tilt = true;
      else if (name == "decentre" || name == "decenter") o.decentre = true;
      else if (name == "clocking") o.clocking = true;
      else throw InputError(at, "compensation.register takes piston, tilt, decentre and clocking, not '" + name + "'");
    }
  }
  o.zernike_terms = 36;
  // Where a smoothing the registration finds too heavy is reported: its value, or the
  // bspline map that takes the default.
  std::optional<SourceLocation> smoothing_at;
  if (map.has("fit")) {
    MapReader fit(map.child("fit"), job_file, "compensation.fit");
    o.zernike_terms = static_cast<int>(fit.in_range("zernike", 36, 1, 231, false, " terms"));
    if (fit.has("zernike") && o.zernike_terms != fit.number("zernike"))
      fit.fail("zernike", "compensation.fit.zernike is a whole number of terms");
    o.outlier_sigmas = fit.in_range("outlier_sigmas", 5, 2, 100, false, "");
    if (fit.has("bspline")) {
      MapReader b(fit.child("bspline"), job_file, "compensation.fit.bspline");
      const double control = b.in_range("control_points", 4, 100, false, " per side");
      if (control != std::floor(control))
        b.fail("control_points", "compensation.fit.bspline.control_points is a whole number");
      o.bspline_control = static_cast<int>(control);
      // A round aperture leaves the square's corners without data: a little smoothing
      // fills them (and no more) unless the job asks for more.
      o.bspline_smoothing = b.non_negative("smoothing", 1e-7);
      smoothing_at =
          location_of(b.has("smoothing") ? b.child("smoothing") : fit.child("bspline"), job_file);
      b.finish();
    }
    fit.finish();
  }
  o.normalization_radius = aperture.outer_radius;
  o.inner_radius = aperture.inner_radius;
  o.outer_radius = aperture.outer_radius;
  map.finish();
  // What is wrong with the measurement as a whole (no valid point, too few inside the
  // aperture, points on a line) has no line of its own in the data: it is reported at the
  // job's `measured` key, naming the file. A bad line of the data keeps its own place.
  const SourceLocation measured_at = map.place("measured");
  const auto at_measured_key = [&](const InputError& e) {
    return InputError(measured_at, "compensation.measured '" + part.file + "': " + e.problem());
  };
  Measurement m;
  try {
    m = read_measurement(path, read);
  } catch (const InputError& e) {
    if (e.where() != path) throw;
    throw at_measured_key(e);
  }
  for (Eigen::Vector3d& p : m.points) p -= Eigen::Vector3d(origin_x, origin_y, 0);
  part.invalid = m.invalid;
  part.points = static_cast<long>(m.points.size());
  if (!o.profile && m.profile)
    map.fail("format", "a profile needs format: profile");
  try {
    part.registration = register_measurement(design, m, o, path);
  } catch (const InputError& e) {
    if (e.where() == path) throw at_measured_key(e);
    if (e.where() != "smoothing" || !smoothing_at) throw;
    throw InputError(*smoothing_at, "compensation.fit.bspline.smoothing " + e.problem() +
                                        " (the B-spline fit of the error)");
  }
  return part;
}

}  // namespace

std::unique_ptr<Surface> read_compensation(const YAML::Node& node, const std::string& job_file,
                                           std::unique_ptr<Surface> design, const Aperture& aperture,
                                           std::vector<MeasuredPart>& parts) {
  std::vector<YAML::Node> entries;
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) entries.push_back(item);
  } else {
    entries.push_back(node);
  }
  if (entries.empty())
    throw InputError(location_of(node, job_file), "compensation: lists no measured part");
  std::vector<CorrectedSurface::Correction> corrections;
  for (const YAML::Node& entry : entries) {
    // Every part is measured against the design (its error is its height beyond the
    // design's), so the corrections add: design − Σ gain · error.
    parts.push_back(read_part(entry, job_file, *design, aperture));
    const Registration& r = parts.back().registration;
    // The fitted Zernike sum expanded into powers of x and y once: the planner evaluates it
    // hundreds of times a cutter point.
    corrections.push_back({std::make_unique<PolynomialHeight>(
                               PolynomialHeight::from_zernike(r.normalization_radius, r.zernike)),
                           parts.back().gain});
    if (r.bspline) corrections.push_back({std::make_unique<NurbsHeightField>(*r.bspline), parts.back().gain});
  }
  return std::make_unique<CorrectedSurface>(std::move(design), std::move(corrections));
}

}  // namespace freeturn::detail
