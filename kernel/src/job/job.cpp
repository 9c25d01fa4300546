#include "freeturn/job/job.hpp"

#include "freeturn/job/surface_yaml.hpp"
#include "freeturn/job/yaml_reader.hpp"
#include "compensation_yaml.hpp"
#include "job_plan_yaml.hpp"

namespace freeturn {
namespace {

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

// Every map key's dotted path and its value's place (sequences by index: "a.b[2]").
void record_places(const YAML::Node& node, const std::string& prefix, const std::string& file,
                   std::map<std::string, SourceLocation>& places) {
  if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (!it->first.IsScalar()) continue;
      const std::string key = prefix.empty() ? it->first.Scalar() : prefix + "." + it->first.Scalar();
      places.emplace(key, location_of(it->second, file));
      record_places(it->second, key, file, places);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string key = prefix + "[" + std::to_string(i) + "]";
      places.emplace(key, location_of(node[i], file));
      record_places(node[i], key, file, places);
    }
  }
}

}  // namespace

SourceLocation Job::place(const std::string& key) const {
  // A setting left to its default has no place of its own: the section that would hold it
  // ("tool" for tool.included_angle_deg) is where to add it.
  for (std::string k = key; !k.empty();) {
    const auto it = places.find(k);
    if (it != places.end()) return it->second;
    const auto dot = k.rfind('.');
    k = dot == std::string::npos ? std::string() : k.substr(0, dot);
  }
  return SourceLocation{file, 0, 0};
}

Job load_job(const std::string& path, std::uintmax_t max_bytes) {
  const YAML::Node root = load_yaml_file(path, max_bytes);
  if (!root.IsDefined() || root.IsNull()) throw InputError(path, "the job file is empty");
  MapReader map(root, path, "job");
  Job job;
  job.file = path;
  job.name = map.file_name("name");
  job.aperture = read_aperture(map.child("aperture"), path);
  job.surface = surface_from_yaml(map.child("surface"), path, job.aperture.outer_radius);
  if (const auto compensation = map.optional_child("compensation"))
    job.surface = detail::read_compensation(*compensation, path, std::move(job.surface),
                                            job.aperture, job.compensation);
  job.plan = detail::read_job_plan(map, job.aperture, *job.surface);
  map.finish();
  record_places(root, "", path, job.places);
  return job;
}

}  // namespace freeturn
