#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "freeturn/pipeline/contact_tape.hpp"

using namespace freeturn;

namespace {

// Points whose every field differs, with values that do not round-trip through text.
std::vector<ContactPoint> points(int n, double seed) {
  std::vector<ContactPoint> out(n);
  for (int i = 0; i < n; ++i) {
    ContactPoint& p = out[i];
    const double v = seed + i / 3.0;
    p.theta = v;
    p.r = std::sqrt(v);
    p.point = {std::sin(v), std::cos(v), -v * 1e-7};
    p.normal = {1e-300 * v, -0.0, 1 / (1 + v)};
    p.chord_error = std::nextafter(1e-6, 1.0) * v;
    p.chord_below = i % 2 == 1;
    p.chord_jump = i % 3 == 2;
    p.uncut_residual = i % 5 == 0 ? 0.0 : 1e-9 * v;
    p.stand_off = 2.5e-5;
    p.pass_spacing = std::numeric_limits<double>::denorm_min() * i;
    p.section_curvature = -0.05 * v;
    p.scallop = std::numeric_limits<double>::max() / (1 + i);
  }
  return out;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_bits(const ContactPoint& a, const ContactPoint& b) {
  bool same = same_bits(a.theta, b.theta) && same_bits(a.r, b.r) &&
              same_bits(a.chord_error, b.chord_error) && a.chord_below == b.chord_below &&
              a.chord_jump == b.chord_jump && same_bits(a.uncut_residual, b.uncut_residual) &&
              same_bits(a.stand_off, b.stand_off) && same_bits(a.pass_spacing, b.pass_spacing) &&
              same_bits(a.section_curvature, b.section_curvature) &&
              same_bits(a.scallop, b.scallop);
  for (int k = 0; k < 3; ++k)
    same = same && same_bits(a.point[k], b.point[k]) && same_bits(a.normal[k], b.normal[k]);
  return same;
}

// Keeps every chunk as it came.
struct ChunkLog final : ContactSink {
  std::vector<std::vector<ContactPoint>> chunks;
  void write(std::span<const ContactPoint> chunk) override {
    chunks.emplace_back(chunk.begin(), chunk.end());
  }
};

}  // namespace

TEST_SUITE("pipeline") {
  TEST_CASE("a contact tape passes its chunks on and replays them bit for bit, as they came") {
    const std::vector<std::vector<ContactPoint>> sent = {
        points(3, 0.1), points(4096, 7.0), {}, points(1, -2.0)};
    ContactTape tape(std::size_t{1} << 30);
    ChunkLog passed, replayed;
    RecordingSink recorder(passed, tape);
    for (const auto& chunk : sent) recorder.write(chunk);
    CHECK(tape.complete());
    tape.replay(replayed);
    tape.replay(replayed);  // a tape can be played again
    REQUIRE(passed.chunks.size() == sent.size());
    REQUIRE(replayed.chunks.size() == 2 * sent.size());
    for (std::size_t c = 0; c < replayed.chunks.size(); ++c) {
      const auto& want = sent[c % sent.size()];
      REQUIRE(replayed.chunks[c].size() == want.size());
      REQUIRE(passed.chunks[c % sent.size()].size() == want.size());
      for (std::size_t i = 0; i < want.size(); ++i) {
        CHECK(same_bits(replayed.chunks[c][i], want[i]));
        CHECK(same_bits(passed.chunks[c % sent.size()][i], want[i]));
      }
    }
  }

  TEST_CASE("a path longer than the tape's bound leaves it incomplete, and it replays nothing") {
    // A chunk of n points takes 8 + 120 n bytes: two of 10 points fit in 2 × 1208, not three.
    ContactTape tape(2 * 1208);
    ChunkLog passed, replayed;
    RecordingSink recorder(passed, tape);
    recorder.write(points(10, 1.0));
    recorder.write(points(10, 2.0));
    CHECK(tape.complete());
    recorder.write(points(10, 3.0));
    CHECK_FALSE(tape.complete());
    recorder.write(points(1, 4.0));  // stays incomplete: a later small chunk is not kept
    CHECK_FALSE(tape.complete());
    CHECK(passed.chunks.size() == 4);  // the tee still passes everything on
    tape.replay(replayed);
    CHECK(replayed.chunks.empty());
  }
}
