#pragma once
// An input file named in a job (a measurement, a point cloud, an IGES surface, an NC
// program) before it is read: it must exist and be a regular file. A directory reads as
// empty and a device or pipe as a stream without end (/dev/zero had been read as one line
// growing until memory ran out), so both are refused by name.

#include <string>

namespace freeturn {

// Throws InputError at `path`: "no such <what>", or "is not a regular file (a directory,
// device or pipe): give <what>". `what` names the file's role ("an NC program").
void require_regular_file(const std::string& path, const std::string& what);

}  // namespace freeturn
