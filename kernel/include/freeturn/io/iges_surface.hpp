#pragma once
// Reading rational B-spline surfaces (entity 128) from an IGES 5.3 file.
//
// The file is fixed-format: 80-column records, the section letter (S, G, D, P, T) in
// column 73. The global section gives the delimiters and the length unit; each directory
// entry (two records) points at its parameter data; entity 128's parameters are
// K1, K2, M1, M2, PROP1-5, the knots S and T, the weights and control points with the
// u index varying fastest, and the parameter range U0, U1, V0, V1. A transformation
// matrix (entity 124) referenced by the entry is applied to the control points, and
// lengths are converted to millimetres.

#include <string>
#include <vector>

#include "freeturn/nurbs/surface.hpp"

namespace freeturn {

struct IgesSurfaceEntry {
  int directory_line = 0;  // sequence number of the entity's first directory record
  nurbs::NurbsSurface surface;
};

// Every entity 128 in the file, in directory order. Throws InputError naming
// "file:line" for a malformed file, an unsupported unit, or a parameter range narrower
// than the knot vectors (a trimmed sub-patch, which is not supported).
std::vector<IgesSurfaceEntry> read_iges_surfaces(const std::string& path);

// The one entity 128 of the file, or the one whose directory entry starts on
// `directory_line` (> 0); an error lists the candidates when the choice is ambiguous.
nurbs::NurbsSurface read_iges_surface(const std::string& path, int directory_line = 0);

}  // namespace freeturn
