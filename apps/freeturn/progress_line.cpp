#include "progress_line.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace freeturn::cli {
namespace {

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Progress::Progress(bool enabled, std::string label) : enabled_(enabled), label_(std::move(label)) {
  start_ = last_print_ = now_seconds();
  // Tests set a zero interval to see a line from a short job.
  if (const char* v = std::getenv("FREETURN_PROGRESS_INTERVAL")) interval_ = std::atof(v);
}

void Progress::update(double, double r, long points) {
  if (!enabled_) return;
  if (first_r_ < 0) first_r_ = r;
  const double t = now_seconds();
  if (t - last_print_ < interval_) return;
  last_print_ = t;
  const double elapsed = t - start_;
  const double done = first_r_ > 0 ? std::clamp(1 - r / first_r_, 0.0, 1.0) : 0.0;
  // Area swept grows as 1 − (r/r₀)², which tracks the point count on a spiral better.
  const double fraction = 1 - (1 - done) * (1 - done);
  const double left = fraction > 0.01 ? elapsed * (1 - fraction) / fraction : 0;
  std::fprintf(stderr, "\r%s: %ld points, %.0f points/s, %3.0f%%, about %.0f s left   ",
               label_.c_str(), points, points / std::max(elapsed, 1e-9), 100 * fraction, left);
  std::fflush(stderr);
}

void Progress::done() {
  if (enabled_) std::fprintf(stderr, "\r%*s\r", 80, "");
}

}  // namespace freeturn::cli
