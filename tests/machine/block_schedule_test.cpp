// Block times the machine can follow: every figure is read back from the scheduled records
// alone, the way a program is read (velocity Δq/t, acceleration |Δv|/min(t1, t2), from
// and to rest), and compared with the machine's limits.
#include "freeturn/machine/block_schedule.hpp"
#include "machine/fixtures.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace freeturn;

namespace {

MachineDescription machine() {
  return test::moore_250upl_xzc();
}

struct Figures {
  double velocity[3] = {0, 0, 0}, acceleration[3] = {0, 0, 0}, rate = 0, total = 0;
};

// Read back as from a program: the first record is the start, at rest.
Figures read_back(const std::vector<AxisRecord>& r) {
  Figures f;
  double v_prev[3] = {0, 0, 0}, t_prev = 0;
  for (std::size_t k = 1; k < r.size(); ++k) {
    const double t = r[k].time;
    REQUIRE(t > 0);
    f.total += t;
    f.rate = std::max(f.rate, 1 / t);
    const double d[3] = {r[k].x - r[k - 1].x, r[k].z - r[k - 1].z,
                         std::remainder(r[k].c - r[k - 1].c, 360.0)};
    const double shorter = k == 1 ? t : std::min(t, t_prev);
    for (int a = 0; a < 3; ++a) {
      const double v = d[a] / t;
      f.velocity[a] = std::max(f.velocity[a], std::abs(v));
      f.acceleration[a] = std::max(f.acceleration[a], std::abs(v - v_prev[a]) / shorter);
      v_prev[a] = v;
    }
    t_prev = t;
  }
  for (int a = 0; a < 3; ++a)
    f.acceleration[a] = std::max(f.acceleration[a], std::abs(v_prev[a]) / t_prev);
  return f;
}

void check_within(const Figures& f, const MachineDescription& m) {
  for (int a = 0; a < 3; ++a) {
    CAPTURE(a);
    CHECK(f.velocity[a] <= m.axes[a].max_velocity);
    CHECK(f.acceleration[a] <= m.axes[a].max_acceleration);
  }
  CHECK(f.rate <= m.max_block_rate);
}

std::vector<AxisRecord> schedule(const MachineDescription& m, const std::vector<AxisRecord>& in,
                                 std::size_t chunk, ScheduleOptions o, ScheduleReport* report) {
  AxisCollector out;
  BlockScheduler s(m, out, o);
  for (std::size_t k = 0; k < in.size(); k += chunk)
    s.write(std::span<const AxisRecord>(in.data() + k, std::min(chunk, in.size() - k)));
  s.finish();
  if (report) *report = s.report();
  return out.records;
}

}  // namespace

TEST_SUITE("machine") {
  TEST_CASE("schedule: blocks the machine can follow keep their nominal time (to the µs above)") {
    // A spiral at 30 rpm: 3.6° in 0.02 s, X creeping 1 µm per block.
    std::vector<AxisRecord> in;
    for (int k = 0; k <= 2000; ++k)
      in.push_back({4 - 1e-3 * k, 1.0, std::fmod(3.6 * k, 360.0), 0, k ? 0.02 : 0.0});
    ScheduleReport report;
    const auto out = schedule(machine(), in, 4096, {}, &report);
    REQUIRE(out.size() == in.size());
    // The first block starts from rest: C reaches 180°/s in one block at 9000°/s² < 30000.
    for (std::size_t k = 1; k < out.size(); ++k)
      CHECK(out[k].time == doctest::Approx(0.02).epsilon(1e-12));
    CHECK(report.slowed_blocks == 0);
    const Figures f = read_back(out);
    check_within(f, machine());
    CHECK(report.cycle_time == doctest::Approx(f.total).epsilon(1e-12));
    CHECK(report.cycle_time == doctest::Approx(40.0).epsilon(1e-12));
  }

  TEST_CASE("schedule: a nominal time between whole µs is written rounded up and not slowed") {
    // 3.6° in 1/30 s (18 rpm): each block is written as 0.033334 s, the nominal time rounded
    // up to the µs, and the machine's limits (C at 108°/s) slow none of them.
    std::vector<AxisRecord> in;
    for (int k = 0; k <= 2000; ++k)
      in.push_back({4 - 1e-3 * k, 1.0, std::fmod(3.6 * k, 360.0), 0, k ? 1.0 / 30 : 0.0});
    ScheduleReport report;
    const auto out = schedule(machine(), in, 4096, {}, &report);
    REQUIRE(out.size() == in.size());
    for (std::size_t k = 1; k < out.size(); ++k)
      CHECK(out[k].time == doctest::Approx(0.033334).epsilon(1e-12));
    CHECK(report.slowed_blocks == 0);
    CHECK(report.cycle_time == doctest::Approx(2000 * 0.033334).epsilon(1e-12));
  }

  TEST_CASE("schedule: a block the next one's speed would leave crawling slows the next instead") {
    // X creeps −1 µm a block, jumps −0.3 mm in one (a pivot's swing), then steps +10 µm a
    // block at the speed s₁ where 0.01·s₁² sits 1e-9 under X's 490 mm/s²: at s₁ the swing's
    // block may run at most 0.3·v·s₁ ≤ 490·1e-9, v = 7e-9 /s, a block of 4.5 years. With
    // the next block at s₁/2 the swing runs at v = (4.43 − 1.11)/0.3 = 11 /s: the pair in
    // 0.1 s. (Seen with B following on an ISO lathe: a cycle of 400 000 years.)
    const double a = 0.98 * 500, s1 = std::sqrt(a * (1 - 1e-9) / 0.01);
    std::vector<AxisRecord> in;
    double x = 4;
    for (int k = 0; k <= 400; ++k) {
      double t = k ? 0.02 : 0.0;
      if (k <= 200) {
        x -= k ? 1e-3 : 0.0;
      } else if (k == 201) {
        x -= 0.3;
      } else {
        x += 0.01;
        t = 1 / s1;
      }
      in.push_back({x, 0.0, 0.0, 0, t});
    }
    double nominal = 0;
    for (const AxisRecord& r : in) nominal += r.time;
    ScheduleReport report;
    const auto out = schedule(machine(), in, 4096, {}, &report);
    const Figures f = read_back(out);
    check_within(f, machine());
    CHECK(out[201].time + out[202].time <= 0.2);
    CHECK(report.cycle_time <= nominal + 1.0);
    CHECK(report.cycle_time == doctest::Approx(f.total).epsilon(1e-12));
  }

  TEST_CASE("schedule: a burst of fast X motion is slowed there only, within every limit") {
    // 2000 blocks at 0.01 s; blocks 900-1100 move X by ±0.4 mm (a 40 mm/s request,
    // alternating: the hardest case for acceleration).
    std::vector<AxisRecord> in;
    double x = 0;
    for (int k = 0; k <= 2000; ++k) {
      if (k >= 900 && k < 1100)
        x += (k % 2 ? 0.4 : -0.4);
      else
        x += 1e-4;
      in.push_back({x, 0.0, std::fmod(1.8 * k, 360.0), 0, k ? 0.01 : 0.0});
    }
    ScheduleReport report;
    const auto out = schedule(machine(), in, 1000, {}, &report);
    const Figures f = read_back(out);
    check_within(f, machine());
    CHECK(report.cycle_time == doctest::Approx(f.total).epsilon(1e-12));
    // Reversing 0.4 mm each block: two blocks of equal time t would need 0.8/t ≤ 490·t, so
    // a pair of blocks takes at least 2·√(0.8/490) (blocks of unequal times take longer).
    for (int k = 901; k < 1098; k += 2)
      CHECK(out[k].time + out[k + 1].time >= 2 * std::sqrt(0.8 / 490) * (1 - 1e-9));
    // Far from the burst the nominal time holds.
    for (int k = 1; k < 700; ++k) CHECK(out[k].time == doctest::Approx(0.01).epsilon(1e-12));
    for (int k = 1400; k <= 2000; ++k) CHECK(out[k].time == doctest::Approx(0.01).epsilon(1e-12));
    CHECK(report.slowed_blocks > 200);
    CHECK(report.slowed_blocks < 600);
  }

  TEST_CASE(
      "schedule: random motion stays within the limits, the same for any chunking and window") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> step(-0.05, 0.05), angle(0.5, 4.0), time(0.001, 0.02);
    std::vector<AxisRecord> in;
    AxisRecord r{1, 0, 0, 0, 0};
    for (int k = 0; k <= 30000; ++k) {
      if (k) {
        r.x += step(rng);
        r.z += 0.3 * step(rng);
        r.c = std::fmod(r.c + angle(rng), 360.0);
        r.time = time(rng);
      }
      in.push_back(r);
    }
    ScheduleReport a, b;
    const auto one = schedule(machine(), in, 4096, {}, &a);
    const auto two = schedule(machine(), in, 777, {}, &b);
    REQUIRE(one.size() == two.size());
    bool same = true;
    for (std::size_t k = 0; k < one.size(); ++k) same = same && one[k].time == two[k].time;
    CHECK(same);
    check_within(read_back(one), machine());
    // A small window is as safe: the stops it plans for are nearer.
    ScheduleOptions small;
    small.window = 64;
    ScheduleReport c;
    const auto three = schedule(machine(), in, 4096, small, &c);
    check_within(read_back(three), machine());
    CHECK(c.cycle_time == doctest::Approx(a.cycle_time).epsilon(0.05));
    // No block is faster than its own velocity and rate limits allow.
    double lower = 0;
    for (std::size_t k = 1; k < in.size(); ++k)
      lower += std::max({in[k].time, std::abs(in[k].x - in[k - 1].x) / 25.0,
                         std::abs(in[k].z - in[k - 1].z) / 25.0, 1 / 2000.0});
    CHECK(a.cycle_time >= lower);
    MESSAGE("random: scheduled ", a.cycle_time, " s against a lower bound of ", lower, " s");
  }

  TEST_CASE(
      "schedule: read back from the words as written (each axis at its decimals), within "
      "the limits where their rounding is a large share of them") {
    // Z at 0.001 mm/s² (the least a machine file takes) stepping ±10 µm about a slow drift:
    // pairs of blocks are held at the acceleration limit, about 0.2 s each, where a word's
    // rounding (half a nanometre at 6 decimals) moves a velocity by 5e-6 mm/s, 2.5 % of
    // the change the limit allows. Planned on the unrounded path, this schedule read 1.9 %
    // over the limit from its words.
    MachineDescription m = machine();
    m.axes[1].max_acceleration = 0.001;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> jitter(-1e-6, 1e-6);
    std::vector<AxisRecord> in;
    for (int k = 0; k <= 400; ++k)
      in.push_back({1 - 1e-4 * k, (k % 2 ? 1e-5 : -1e-5) + 1e-5 * std::sin(0.01 * k) + jitter(rng),
                    std::fmod(1.8 * k, 360.0), 0, k ? 0.01 : 0.0});
    const auto out = schedule(m, in, 1000, {}, nullptr);
    // The records as the post's words carry them: rounded to nearest at 6, 6 and 5 decimals.
    std::vector<AxisRecord> written = out;
    for (AxisRecord& r : written) {
      r.x = std::nearbyint(r.x * 1e6) / 1e6;
      r.z = std::nearbyint(r.z * 1e6) / 1e6;
      r.c = std::nearbyint(r.c * 1e5) / 1e5;
    }
    const Figures f = read_back(written);
    MESSAGE("Z's acceleration read back from the words: ", f.acceleration[1], " mm/s²");
    check_within(f, m);
    // The limit binds: the margin's share of it is reached, to the µs rounding of the times.
    CHECK(f.acceleration[1] > 0.97 * 0.001);
  }
}
