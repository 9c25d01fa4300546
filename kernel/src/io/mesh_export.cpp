#include "freeturn/io/mesh_export.hpp"

// OpenMesh's property containers trip GCC 12's -Wmaybe-uninitialized at -O1 (ASan builds).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"
#include "freeturn/io/atomic_file.hpp"

namespace freeturn {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
  VertexAttributes(OpenMesh::Attributes::Normal);
  FaceAttributes(OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

// One line: `prefix` then the three numbers, each the shortest text that reads back as the
// same double (locale-free, core/number_text.hpp).
void put(AtomicFile& f, const char* prefix, double a, double b, double c) {
  std::string line = prefix;
  for (const double v : {a, b, c}) line += (line.empty() ? "" : " ") + shortest_text(v);
  f.write(line + "\n");
}

}  // namespace

MeshSummary write_surface_mesh_obj(const Surface& surface, double inner, double outer, int rings,
                                   int segments, AtomicFile& f) {
  if (rings < 1 || segments < 3)
    throw InputError(f.path(), "a surface mesh needs rings ≥ 1 and segments ≥ 3");
  Mesh mesh;
  std::vector<std::vector<Mesh::VertexHandle>> ring_vertices;
  const bool centre = inner == 0;
  Mesh::VertexHandle centre_vertex;
  if (centre) centre_vertex = mesh.add_vertex(Mesh::Point(0, 0, surface.sag(0, 0)));
  for (int i = centre ? 1 : 0; i <= rings; ++i) {
    const double r = inner + (outer - inner) * i / rings;
    ring_vertices.emplace_back();
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * std::numbers::pi * j / segments;
      const double x = r * std::cos(phi), y = r * std::sin(phi), z = surface.sag(x, y);
      if (!std::isfinite(z)) {
        throw InputError("(x, y) = (" + fixed_text(x, 6) + ", " + fixed_text(y, 6) + ") mm",
                         "the surface is undefined here");
      }
      ring_vertices.back().push_back(mesh.add_vertex(Mesh::Point(x, y, z)));
    }
  }
  // Counter-clockwise seen from +z: normals toward the tool.
  if (centre)
    for (int j = 0; j < segments; ++j)
      mesh.add_face(centre_vertex, ring_vertices[0][j], ring_vertices[0][(j + 1) % segments]);
  for (std::size_t i = 0; i + 1 < ring_vertices.size(); ++i)
    for (int j = 0; j < segments; ++j) {
      const int k = (j + 1) % segments;
      mesh.add_face(ring_vertices[i][j], ring_vertices[i + 1][j], ring_vertices[i + 1][k]);
      mesh.add_face(ring_vertices[i][j], ring_vertices[i + 1][k], ring_vertices[i][k]);
    }
  mesh.update_normals();
  f.write("# design surface, written by freeturn (mm)\n");
  for (const auto v : mesh.vertices()) {
    const Mesh::Point& p = mesh.point(v);
    put(f, "v", p[0], p[1], p[2]);
  }
  for (const auto v : mesh.vertices()) {
    const Mesh::Normal& n = mesh.normal(v);
    put(f, "vn", n[0], n[1], n[2]);
  }
  for (const auto fh : mesh.faces()) {
    char line[96];
    int n = 1;
    line[0] = 'f';
    for (const auto v : mesh.fv_range(fh))
      n += std::snprintf(line + n, sizeof line - static_cast<std::size_t>(n), " %d//%d",
                         v.idx() + 1, v.idx() + 1);
    line[n++] = '\n';
    f.write(std::string_view(line, static_cast<std::size_t>(n)));
  }
  return {static_cast<long>(mesh.n_vertices()), static_cast<long>(mesh.n_faces())};
}

MeshSummary write_surface_mesh_obj(const Surface& surface, double inner_radius, double outer_radius,
                                   int rings, int segments, const std::string& path) {
  AtomicFile f(path);
  const MeshSummary summary =
      write_surface_mesh_obj(surface, inner_radius, outer_radius, rings, segments, f);
  f.commit();
  return summary;
}

void write_polyline_vtk(const std::vector<Eigen::Vector3d>& points, AtomicFile& f) {
  std::string head =
      "# vtk DataFile Version 3.0\nfreeturn tool path (mm)\nASCII\nDATASET POLYDATA\nPOINTS ";
  head += std::to_string(points.size());
  head += " double\n";
  f.write(head);
  for (const Eigen::Vector3d& p : points) put(f, "", p.x(), p.y(), p.z());
  std::string lines = "LINES 1 ";
  lines += std::to_string(points.size() + 1);
  lines += "\n";
  lines += std::to_string(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    lines += ' ';
    lines += std::to_string(i);
  }
  lines += '\n';
  f.write(lines);
}

void write_polyline_vtk(const std::vector<Eigen::Vector3d>& points, const std::string& path) {
  AtomicFile f(path);
  write_polyline_vtk(points, f);
  f.commit();
}

}  // namespace freeturn

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
