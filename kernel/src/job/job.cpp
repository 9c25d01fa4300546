#include "freeturn/job/job.hpp"

#include "freeturn/job/surface_yaml.hpp"
#include "freeturn/job/yaml_reader.hpp"
#include "job_plan_yaml.hpp"

namespace freeturn {
namespace {

bool is_file_name_safe(const std::string& name) {
  if (name.empty() || name[0] == '.') return false;
  for (char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                    (ch >= '0' && ch <= '9') || ch == '-' || ch == '_' || ch == '.';
    if (!ok) return false;
  }
  return true;
}

Aperture read_aperture(const YAML::Node& node, const std::string& file) {
  MapReader map(node, file, "aperture");
  Aperture a;
  a.outer_radius = map.positive("outer_radius");
  a.inner_radius = map.non_negative("inner_radius", 0.0);
  if (a.inner_radius >= a.outer_radius)
    map.fail("inner_radius", "aperture.inner_radius must be smaller than outer_radius");
  map.finish();
  return a;
}

}  // namespace

Job load_job(const std::string& path, std::uintmax_t max_bytes) {
  const YAML::Node root = load_yaml_file(path, max_bytes);
  if (!root.IsDefined() || root.IsNull()) throw InputError(path, "the job file is empty");
  MapReader map(root, path, "job");
  Job job;
  job.file = path;
  job.name = map.text("name");
  if (!is_file_name_safe(job.name))
    map.fail("name", "job name '" + job.name +
                         "' must use only letters, digits, '-', '_' and '.' (it names files)");
  job.aperture = read_aperture(map.child("aperture"), path);
  job.surface = surface_from_yaml(map.child("surface"), path, job.aperture.outer_radius);
  job.plan = detail::read_job_plan(map, job.aperture);
  map.finish();
  return job;
}

}  // namespace freeturn
