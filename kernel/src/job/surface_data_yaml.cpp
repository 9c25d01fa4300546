#include "surface_data_yaml.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "freeturn/io/iges_surface.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/xyz_points.hpp"
#include "freeturn/nurbs/interpolation.hpp"
#include "freeturn/nurbs/least_squares.hpp"
#include "freeturn/surface/nurbs_height_field.hpp"

namespace freeturn::detail {
namespace {

// A path in the job relative to the job file's directory.
std::string resolve(const MapReader& map, const std::string& key) {
  const std::filesystem::path p(map.node()[key].Scalar());
  if (p.is_absolute()) return p.string();
  return (std::filesystem::path(map.file()).parent_path() / p).lexically_normal().string();
}

double number_at(const YAML::Node& v, const MapReader& map, const std::string& what) {
  double x;
  if (!v.IsScalar() || !YAML::convert<double>::decode(v, x) || !std::isfinite(x))
    throw InputError(location_of(v, map.file()), what + " must be a finite number");
  return x;
}

std::vector<double> number_list(MapReader& map, const std::string& key) {
  const YAML::Node node = map.child(key);
  if (!node.IsSequence() || node.size() == 0)
    throw InputError(location_of(node, map.file()), "surface." + key + " must be a list of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i)
    out.push_back(number_at(node[i], map, "surface." + key + "[" + std::to_string(i) + "]"));
  return out;
}

std::vector<Eigen::Vector3d> point_list(MapReader& map, const std::string& key) {
  const YAML::Node node = map.child(key);
  if (!node.IsSequence() || node.size() == 0)
    throw InputError(location_of(node, map.file()),
                     "surface." + key + " must be a list of [x, y, z] points");
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string what = "surface." + key + "[" + std::to_string(i) + "]";
    if (!node[i].IsSequence() || node[i].size() != 3)
      throw InputError(location_of(node[i], map.file()), what + " must be [x, y, z]");
    out.emplace_back(number_at(node[i][0], map, what), number_at(node[i][1], map, what),
                     number_at(node[i][2], map, what));
  }
  return out;
}

int small_integer(MapReader& map, const std::string& key, int fallback, int lo, int hi) {
  const double v = map.number(key, fallback);
  if (v != std::floor(v) || v < lo || v > hi)
    map.fail(key, "surface." + key + " must be an integer from " + std::to_string(lo) + " to " +
                      std::to_string(hi));
  return static_cast<int>(v);
}

std::unique_ptr<Surface> height_field(MapReader& map, const std::string& key,
                                      nurbs::NurbsSurface surface) {
  try {
    return std::make_unique<NurbsHeightField>(std::move(surface));
  } catch (const InputError& e) {
    map.fail(key, e.problem());
  }
}

// Sorted distinct values of one coordinate, merging those closer than `tolerance`.
std::vector<double> distinct(std::vector<double> values, double tolerance) {
  std::sort(values.begin(), values.end());
  std::vector<double> out;
  for (double v : values)
    if (out.empty() || v - out.back() > tolerance) out.push_back(v);
  return out;
}

std::vector<double> normalised(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values) out.push_back((v - values.front()) / (values.back() - values.front()));
  out.back() = 1.0;
  return out;
}

}  // namespace

std::unique_ptr<Surface> read_nurbs_surface(MapReader& map) {
  if (map.has("iges")) {
    const std::string path = resolve(map, "iges");
    map.text("iges");
    const int entity = map.has("entity") ? small_integer(map, "entity", 0, 1, 1 << 30) : 0;
    nurbs::NurbsSurface s;
    try {
      s = read_iges_surface(path, entity);
    } catch (const InputError& e) {
      map.fail(map.has("entity") ? "entity" : "iges",
               (e.where().empty() ? "" : e.where() + ": ") + e.problem());
    }
    return height_field(map, "iges", std::move(s));
  }
  const int pu = small_integer(map, "degree_u", 3, 1, 9), pv = small_integer(map, "degree_v", 3, 1, 9);
  const std::vector<double> ku = number_list(map, "knots_u"), kv = number_list(map, "knots_v");
  const std::vector<Eigen::Vector3d> points = point_list(map, "points");
  const std::vector<double> weights =
      map.has("weights") ? number_list(map, "weights") : std::vector<double>{};
  const long nu = static_cast<long>(ku.size()) - pu - 1, nv = static_cast<long>(kv.size()) - pv - 1;
  if (nu < pu + 1 || nv < pv + 1)
    map.fail(nu < pu + 1 ? "knots_u" : "knots_v",
             "too few knots for the degree: a degree-p direction with n control points has "
             "n + p + 1 knots and n ≥ p + 1");
  if (static_cast<long>(points.size()) != nu * nv)
    map.fail("points", "the knots give " + std::to_string(nu) + " × " + std::to_string(nv) +
                           " control points (u-major: " + std::to_string(nv) +
                           " per row); the list has " + std::to_string(points.size()));
  if (!weights.empty() && weights.size() != points.size())
    map.fail("weights", "needs one weight per control point (" + std::to_string(points.size()) + ")");
  nurbs::NurbsSurface s;
  try {
    s = nurbs::NurbsSurface(pu, pv, ku, kv, points, weights);
  } catch (const InputError& e) {
    // The kernel names the datum ("u knot 4", "weight 1,2", "control point 0,3"): the
    // error goes to it in the file, not to the whole surface.
    const std::string& where = e.where();
    const auto index_after = [&](const std::string& prefix, int& a, int& b) {
      if (where.rfind(prefix, 0) != 0) return false;
      return std::sscanf(where.c_str() + prefix.size(), "%d,%d", &a, &b) >= 1;
    };
    int a = -1, b = -1;
    std::string key = "points";
    long element = -1;
    if (where.rfind("u ", 0) == 0 || where.rfind("v ", 0) == 0) {
      key = where[0] == 'u' ? "knots_u" : "knots_v";
      if (index_after(where.substr(0, 2) + "knot ", a, b)) element = a;
    } else if (index_after("weight ", a, b)) {
      key = "weights";
      element = b >= 0 ? static_cast<long>(a) * nv + b : a;
    } else if (where.rfind("weights", 0) == 0) {
      key = "weights";
    } else if (index_after("control point ", a, b)) {
      element = b >= 0 ? static_cast<long>(a) * nv + b : a;
    }
    const YAML::Node list = map.node()[key];
    if (element >= 0 && list && list.IsSequence() && element < static_cast<long>(list.size()))
      throw InputError(location_of(list[static_cast<std::size_t>(element)], map.file()),
                       "surface." + key + "[" + std::to_string(element) + "] (" + where + ") " +
                           e.problem());
    map.fail(key, "surface." + key + ": " + where + ": " + e.problem());
  }
  return height_field(map, "points", std::move(s));
}

std::unique_ptr<Surface> read_height_grid(MapReader& map) {
  // The grid as rows along x: grid[i·ny + j] = (x_i, y_j, z_ij).
  std::vector<double> xs, ys;
  std::vector<Eigen::Vector3d> grid;
  std::string data_key;
  if (map.has("file")) {
    data_key = "file";
    const std::string path = resolve(map, "file");
    map.text("file");
    std::vector<Eigen::Vector3d> points;
    try {
      points = read_xyz_points(path);
    } catch (const InputError& e) {
      map.fail("file", e.where() + ": " + e.problem());
    }
    Eigen::AlignedBox3d box;
    for (const auto& p : points) box.extend(p);
    const double tolerance = 1e-9 * std::max(1.0, box.diagonal().norm());
    std::vector<double> all_x, all_y;
    for (const auto& p : points) {
      all_x.push_back(p.x());
      all_y.push_back(p.y());
    }
    xs = distinct(all_x, tolerance);
    ys = distinct(all_y, tolerance);
    if (xs.size() * ys.size() != points.size())
      map.fail("file", "the " + std::to_string(points.size()) + " points do not form a regular "
                           "grid: they have " + std::to_string(xs.size()) + " distinct x and " +
                           std::to_string(ys.size()) + " distinct y values");
    grid.assign(points.size(), Eigen::Vector3d::Constant(std::nan("")));
    for (const auto& p : points) {
      const auto i = std::lower_bound(xs.begin(), xs.end(), p.x() - tolerance) - xs.begin();
      const auto j = std::lower_bound(ys.begin(), ys.end(), p.y() - tolerance) - ys.begin();
      Eigen::Vector3d& cell = grid[static_cast<std::size_t>(i) * ys.size() + static_cast<std::size_t>(j)];
      if (!std::isnan(cell.z()))
        map.fail("file", "the point (" + shortest_text(p.x()) + ", " + shortest_text(p.y()) +
                             ") appears twice");
      cell = {xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(j)], p.z()};
    }
  } else {
    data_key = "z";
    xs = number_list(map, "x");
    ys = number_list(map, "y");
    const YAML::Node z = map.child("z");
    if (!z.IsSequence() || z.size() != ys.size())
      throw InputError(location_of(z, map.file()),
                       "surface.z must be a list of " + std::to_string(ys.size()) +
                           " rows (one per y value), each of " + std::to_string(xs.size()) +
                           " heights (one per x value)");
    grid.resize(xs.size() * ys.size());
    for (std::size_t j = 0; j < ys.size(); ++j) {
      if (!z[j].IsSequence() || z[j].size() != xs.size())
        throw InputError(location_of(z[j], map.file()),
                         "surface.z row " + std::to_string(j) + " must have " +
                             std::to_string(xs.size()) + " heights (one per x value)");
      for (std::size_t i = 0; i < xs.size(); ++i)
        grid[i * ys.size() + j] = {xs[i], ys[j],
                                   number_at(z[j][i], map, "surface.z[" + std::to_string(j) + "][" +
                                                               std::to_string(i) + "]")};
    }
    for (const auto* v : {&xs, &ys})
      for (std::size_t k = 1; k < v->size(); ++k)
        if (!((*v)[k] > (*v)[k - 1]))
          map.fail(v == &xs ? "x" : "y", "surface." + std::string(v == &xs ? "x" : "y") +
                                             " must increase strictly");
  }
  const int degree = small_integer(map, "degree", 3, 1, 5);
  if (static_cast<int>(std::min(xs.size(), ys.size())) < degree + 1)
    map.fail(data_key, "a degree-" + std::to_string(degree) + " grid needs at least " +
                           std::to_string(degree + 1) + " values of x and of y");
  const std::string fit = map.has("fit") ? map.text("fit") : "interpolate";
  const int rows = static_cast<int>(xs.size()), cols = static_cast<int>(ys.size());
  // Parameters proportional to x and y: the spline then reproduces x and y exactly, and
  // the height field needs no inversion (NurbsHeightField::affine_parameters).
  nurbs::GridParameters params{normalised(xs), normalised(ys)};
  nurbs::NurbsSurface s;
  if (fit == "interpolate") {
    s = nurbs::interpolate_surface(grid, rows, cols, degree, degree, &params);
  } else if (fit == "least_squares") {
    const YAML::Node cp = map.child("control_points");
    int nu = 0, nv = 0;
    if (!cp.IsSequence() || cp.size() != 2 || !YAML::convert<int>::decode(cp[0], nu) ||
        !YAML::convert<int>::decode(cp[1], nv) || nu < degree + 1 || nv < degree + 1 ||
        nu > rows || nv > cols)
      throw InputError(location_of(cp, map.file()),
                       "surface.control_points must be [count_x, count_y] with " +
                           std::to_string(degree + 1) + " ≤ count_x ≤ " + std::to_string(rows) +
                           " and " + std::to_string(degree + 1) + " ≤ count_y ≤ " +
                           std::to_string(cols));
    nurbs::SurfaceFitOptions o;
    o.degree_u = o.degree_v = degree;
    o.count_u = nu;
    o.count_v = nv;
    o.smoothing = map.non_negative("smoothing", 0.0);
    o.params_u = params.u;
    o.params_v = params.v;
    try {
      s = nurbs::fit_surface_grid(grid, rows, cols, o).surface;
    } catch (const InputError& e) {
      if (e.where() == "smoothing") map.fail("smoothing", "surface.smoothing " + e.problem());
      map.fail("control_points", e.where() + ": " + e.problem());
    }
  } else {
    map.fail("fit", "surface.fit must be interpolate or least_squares, not '" + fit + "'");
  }
  return height_field(map, data_key, std::move(s));
}

std::unique_ptr<Surface> read_point_cloud(MapReader& map) {
  std::vector<Eigen::Vector3d> points;
  std::string data_key = map.has("file") ? "file" : "points";
  if (map.has("file")) {
    const std::string path = resolve(map, "file");
    map.text("file");
    try {
      points = read_xyz_points(path);
    } catch (const InputError& e) {
      map.fail("file", e.where() + ": " + e.problem());
    }
  } else {
    points = point_list(map, "points");
  }
  const int degree = small_integer(map, "degree", 3, 1, 5);
  const YAML::Node cp = map.child("control_points");
  int nu = 0, nv = 0;
  if (!cp.IsSequence() || cp.size() != 2 || !YAML::convert<int>::decode(cp[0], nu) ||
      !YAML::convert<int>::decode(cp[1], nv) || nu < degree + 1 || nv < degree + 1 ||
      static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv) > points.size())
    throw InputError(location_of(cp, map.file()),
                     "surface.control_points must be [count_x, count_y], each at least " +
                         std::to_string(degree + 1) + ", with count_x·count_y at most the " +
                         std::to_string(points.size()) + " points");
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  if (!(box.sizes().x() > 0 && box.sizes().y() > 0))
    map.fail(data_key, "the points span no area in x-y");
  std::vector<double> u, v;
  for (const auto& p : points) {
    u.push_back((p.x() - box.min().x()) / box.sizes().x());
    v.push_back((p.y() - box.min().y()) / box.sizes().y());
  }
  nurbs::SurfaceFitOptions o;
  o.degree_u = o.degree_v = degree;
  o.count_u = nu;
  o.count_v = nv;
  // Uniform knots over the box: the data may be sparse anywhere, and smoothing (or the
  // error below) says so rather than knots that chase the samples.
  for (int k = 0; k <= degree; ++k) {
    o.knots_u.push_back(0.0);
    o.knots_v.push_back(0.0);
  }
  for (int k = 1; k < nu - degree; ++k) o.knots_u.push_back(static_cast<double>(k) / (nu - degree));
  for (int k = 1; k < nv - degree; ++k) o.knots_v.push_back(static_cast<double>(k) / (nv - degree));
  for (int k = 0; k <= degree; ++k) {
    o.knots_u.push_back(1.0);
    o.knots_v.push_back(1.0);
  }
  o.smoothing = map.non_negative("smoothing", 0.0);
  const double tolerance = map.has("tolerance") ? map.positive("tolerance") : 0.0;
  nurbs::SurfaceFit fit;
  try {
    fit = nurbs::fit_surface_scattered(points, u, v, o);
  } catch (const InputError& e) {
    if (e.where() == "smoothing") map.fail("smoothing", "surface.smoothing " + e.problem());
    map.fail("control_points", e.where() + ": " + e.problem() +
                                   " (add smoothing, or fewer control points)");
  }
  if (tolerance > 0 && fit.max_error > tolerance) {
    std::size_t worst = 0;
    double worst_error = -1;
    for (std::size_t k = 0; k < points.size(); ++k) {
      const double e = (fit.surface.point(fit.u[k], fit.v[k]) - points[k]).norm();
      if (e > worst_error) {
        worst_error = e;
        worst = k;
      }
    }
    map.fail("tolerance", "the fit misses point " + std::to_string(worst + 1) + " (" +
                              shortest_text(points[worst].x()) + ", " +
                              shortest_text(points[worst].y()) + ") by " +
                              significant_text(worst_error * 1e3, 6) + " µm, above the tolerance (" +
                              significant_text(tolerance * 1e3, 6) + " µm); rms " +
                              significant_text(fit.rms_error * 1e3, 6) + " µm");
  }
  return height_field(map, data_key, std::move(fit.surface));
}

}  // namespace freeturn::detail
