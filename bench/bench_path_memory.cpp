// Peak memory of a long path: plans a traditional spiral of about 20 million contact
// points (equal angles) into a sink that only counts them, and prints the count and the
// time. Measure the peak resident set with
//   /usr/bin/time -v build/release/bench/bench_path_memory
// ("Maximum resident set size"): it does not grow with the number of points.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "freeturn/path/spiral.hpp"
#include "freeturn/surface/even_asphere.hpp"

namespace {
struct CountingSink final : freeturn::ContactSink {
  void write(std::span<const freeturn::ContactPoint> chunk) override {
    count += static_cast<long>(chunk.size());
    last_r = chunk.back().r;
  }
  long count = 0;
  double last_r = -1;
};
}  // namespace

int main(int argc, char** argv) {
  // Points = revolutions × points per revolution: 10 mm / 0.5 µm × 1000 = 20 million.
  const double pitch = argc > 1 ? std::atof(argv[1]) : 0.0005;
  const freeturn::EvenAsphere sphere(1 / 40.0, 0.0);
  freeturn::SpiralOptions o;
  o.outer_radius = 10.0;
  o.pitch = pitch;
  o.points.rule = freeturn::CutterPointRule::kEqualAngle;
  o.points.points_per_revolution = 1000;
  CountingSink sink;
  const auto t0 = std::chrono::steady_clock::now();
  const freeturn::PathSummary s =
      freeturn::plan_spiral(sphere, freeturn::BaseSurface::plane(10.0), o, sink);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("points %ld (summary %ld), last r %.3g mm, %.2f s, %.3g points/s, max chord error %.3g nm\n",
              sink.count, s.points, sink.last_r, seconds, static_cast<double>(sink.count) / seconds,
              s.max_chord_error * 1e6);
  return sink.count == s.points ? 0 : 1;
}
