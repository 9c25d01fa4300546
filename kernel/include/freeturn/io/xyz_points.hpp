#pragma once
// Measured or exported surface points as text: one point per line, x y z separated by
// commas, semicolons or white space; '#' starts a comment; one header line of names is
// allowed at the top.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace freeturn {

// #P points (mm). Throws InputError at "file:line" for a line that is not three finite
// numbers, and for a file without points.
std::vector<Eigen::Vector3d> read_xyz_points(const std::string& path);

}  // namespace freeturn
