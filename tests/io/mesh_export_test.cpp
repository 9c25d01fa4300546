#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "freeturn/io/mesh_export.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "test_files.hpp"

using namespace freeturn;

TEST_SUITE("io") {
  TEST_CASE("surface mesh: a sphere's vertices on the sphere in double precision, normals toward the tool") {
    test::TempDir dir;
    const EvenAsphere sphere(1 / 20.0, 0);
    const std::string path = dir.file("s.obj");
    const MeshSummary m = write_surface_mesh_obj(sphere, 0, 10, 8, 24, path);
    CHECK(m.vertices == 1 + 8 * 24);
    CHECK(m.faces == 24 + 2 * 24 * 7);
    std::istringstream in(test::read_file(path));
    std::string tag;
    long v = 0, vn = 0, f = 0;
    double worst_radius = 0, worst_normal = 0;
    std::vector<Eigen::Vector3d> points;
    for (std::string line; std::getline(in, line);) {
      std::istringstream l(line);
      l >> tag;
      if (tag == "v") {
        Eigen::Vector3d p;
        l >> p.x() >> p.y() >> p.z();
        points.push_back(p);
        // |p − (0, 0, 20)| = 20: far finer than single precision (~1e-6 mm here).
        worst_radius = std::max(worst_radius, std::abs((p - Eigen::Vector3d(0, 0, 20)).norm() - 20));
        ++v;
      } else if (tag == "vn") {
        Eigen::Vector3d n;
        l >> n.x() >> n.y() >> n.z();
        const Eigen::Vector3d& p = points[static_cast<std::size_t>(vn)];
        worst_normal = std::max(worst_normal, 1 - n.dot(sphere.normal(p.x(), p.y())));
        ++vn;
      } else if (tag == "f") {
        ++f;
      }
    }
    CHECK(v == m.vertices);
    CHECK(vn == m.vertices);
    CHECK(f == m.faces);
    CHECK(worst_radius < 1e-10);
    CHECK(worst_normal < 0.02);  // area-weighted face normals of a coarse mesh, all facing +z
  }

  TEST_CASE("path polyline: legacy VTK with every point and one line through them") {
    test::TempDir dir;
    const std::string path = dir.file("p.vtk");
    write_polyline_vtk({{0, 0, 0}, {1, 2, 3}, {0.5, -1e-7, 2.25}}, path);
    CHECK(test::read_file(path) ==
          "# vtk DataFile Version 3.0\nfreeturn tool path (mm)\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n"
          "0 0 0\n1 2 3\n0.5 -1e-07 2.25\nLINES 1 4\n3 0 1 2\n");
  }
}
