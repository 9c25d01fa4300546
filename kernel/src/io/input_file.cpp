#include "freeturn/io/input_file.hpp"

#include <filesystem>

#include "freeturn/core/error.hpp"

namespace freeturn {

void require_regular_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(SourceLocation{path, 0, 0}, "no such file: give " + what);
  if (!std::filesystem::is_regular_file(status))
    throw InputError(SourceLocation{path, 0, 0},
                     "is not a regular file (a directory, device or pipe): give " + what);
}

}  // namespace freeturn
