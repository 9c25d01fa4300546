#pragma once
// The one error type for bad input: YAML, NURBS data, machine limits exceeded.
// Expected numerical outcomes (no convergence, a ray that misses) are not errors;
// they come back as a Status beside the value (see status.hpp).

#include <stdexcept>
#include <string>
#include <string_view>

namespace freeturn {

// Where in a source file something was found; line and column are 1-based, 0 = unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  // "file:line:col", "file:line", "file", or "" when nothing is known.
  std::string to_string() const;
};

// `text` with every control byte (below 0x20, and DEL) written as \xNN, and every C1
// control and bidirectional format character (U+0080 to U+009F, U+200E, U+200F, U+202A to
// U+202E, U+2066 to U+2069) as \uXXXX, so that a value quoted from the user's file (a
// name, a key, a scalar) cannot put a NUL, a carriage return, a terminal escape or a
// right-to-left override into a message. `keep_newlines` leaves '\n' alone, for
// messages that are laid out on several lines.
std::string escape_control_bytes(std::string_view text, bool keep_newlines = false);

// Its `where` and `what` are kept as given, control bytes escaped (see above; the
// message's own line breaks stay).
class InputError : public std::runtime_error {
 public:
  // `where` is free text naming the place ("job.yaml:3:7", "theta=12.5 rad, r=3.2 mm",
  // "knot 4"); `what` says what is wrong and what was expected.
  InputError(std::string where, const std::string& what);
  InputError(const SourceLocation& where, const std::string& what);
  explicit InputError(const std::string& what) : InputError(std::string(), what) {}
  // `cause` names the job setting whose value leads to the error, as a dotted key
  // ("strategy.mode", "tool.nose_radius"), when the error is found while planning or
  // posting, far from the file: the command line reports it at that key's place in the
  // job file, with `where` (the place on the path) after it.
  InputError(std::string where, const std::string& what, std::string cause)
      : InputError(std::move(where), what) {
    cause_ = std::move(cause);
  }

  const std::string& where() const { return where_; }
  const std::string& problem() const { return problem_; }
  const std::string& cause() const { return cause_; }

 private:
  // Both already escaped.
  InputError(std::string where, std::string what, int);

  std::string where_;
  std::string problem_;
  std::string cause_;
};

// The program a job describes would break a check: a gouge, a contact or clearance angle,
// a travel or B limit, a dynamic limit. The job is well formed; the cut is not safe. The
// command line answers it with exit 1 (a check failed), not 2 (bad input).
// Its cause is the setting the check holds against the design ("tool.nose_radius").
class CheckFailure : public InputError {
 public:
  CheckFailure(std::string where, const std::string& what, std::string cause = {})
      : InputError(std::move(where), what, std::move(cause)) {}
};

}  // namespace freeturn
