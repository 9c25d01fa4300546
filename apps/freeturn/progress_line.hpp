#pragma once
// The progress line on a terminal: points done, rate, estimated time left (from r).

#include <string>

namespace freeturn::cli {

// A progress line on a terminal: points done, rate, estimated time left (from θ or r).
class Progress {
 public:
  Progress(bool enabled, std::string label);
  void update(double theta, double r, long points);
  void done();

 private:
  bool enabled_;
  std::string label_;
  double start_ = 0, last_print_ = 0;
  double interval_ = 0.25;  // s between updates
  double first_r_ = -1;
};

}  // namespace freeturn::cli
