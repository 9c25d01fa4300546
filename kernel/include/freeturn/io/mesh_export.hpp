#pragma once
// Meshes for a look in MeshLab or ParaView: the design surface over the aperture as a
// triangle mesh (OBJ with vertex normals) and the tool path as a polyline (legacy VTK).
//
// The mesh is built and its normals computed with OpenMesh (double-precision traits). It
// is written by freeturn, not by OpenMesh's writers, which go through single precision
// (shared/notes/dependencies.md): float would round a 20 mm part to about 1 µm, far
// coarser than the form errors the report is about.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "freeturn/io/atomic_file.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

struct MeshSummary {
  long vertices = 0, faces = 0;
};

// A polar grid of `rings` × `segments` over inner ≤ r ≤ outer (a single centre vertex
// when inner = 0), triangulated and oriented with normals toward the tool (+z side).
// Written atomically to `path` (OBJ, %.12g), or into `out` for the caller to commit.
MeshSummary write_surface_mesh_obj(const Surface& surface, double inner_radius, double outer_radius,
                                   int rings, int segments, const std::string& path);
MeshSummary write_surface_mesh_obj(const Surface& surface, double inner_radius, double outer_radius,
                                   int rings, int segments, AtomicFile& out);

// #P points as one polyline, legacy VTK POLYDATA (ParaView), written atomically to `path`
// or into `out` for the caller to commit.
void write_polyline_vtk(const std::vector<Eigen::Vector3d>& points, const std::string& path);
void write_polyline_vtk(const std::vector<Eigen::Vector3d>& points, AtomicFile& out);

}  // namespace freeturn
