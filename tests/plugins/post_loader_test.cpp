#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/io/nc_program.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/post_program.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/tool_compensator.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

const std::string kPlugins = FREETURN_PLUGIN_DIR;
const std::string kFixtures = FREETURN_TEST_PLUGIN_DIR;
const std::string kMachines = FREETURN_MACHINE_DIR;

}  // namespace

TEST_SUITE("plugins") {
  TEST_CASE("loader failures each give their own message") {
    CHECK_THROWS_WITH_AS(PostPlugin::load_file(kFixtures + "/missing.so"),
                         doctest::Contains("cannot load the post-processor"), InputError);
    CHECK_THROWS_WITH_AS(PostPlugin::load_file(kFixtures + "/libfreeturn_post_bad_abi.so"),
                         doctest::Contains("post-processor ABI version 99; this freeturn needs version 1"),
                         InputError);
    CHECK_THROWS_WITH_AS(PostPlugin::load_file(kFixtures + "/libfreeturn_post_no_entry.so"),
                         doctest::Contains("does not export freeturn_post_entry"), InputError);
    setenv("FREETURN_PLUGIN_PATH", (kFixtures + ":" + kPlugins).c_str(), 1);
    CHECK_THROWS_WITH_AS(PostPlugin::load("nonexistent"),
                         doctest::Contains("not found: no libfreeturn_post_nonexistent.so in"),
                         InputError);
    const auto failing = PostPlugin::load("failing");
    test::TempDir dir;
    MachineDescription m;
    m.name = "test";
    m.axes = {{Axis::kX}, {Axis::kZ}};
    CHECK_THROWS_WITH_AS(PostProgram(*failing, m, {"job"}, dir.file("out.nc")),
                         doctest::Contains("create: this dialect needs a setting 'program_number'"),
                         InputError);
    // Nothing was left behind.
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 0);
    unsetenv("FREETURN_PLUGIN_PATH");
  }

  TEST_CASE("iso: the program parses back to the axis values at the declared decimals") {
    const MachineDescription m = load_machine(kMachines + "/iso-lathe-xzc.yaml");
    CHECK(m.plugin == "iso");
    CHECK(!m.c_wrapped);
    const auto iso = PostPlugin::load_file(kPlugins + "/libfreeturn_post_iso.so");
    test::TempDir dir;
    const EvenAsphere asphere(1 / 30.0, -0.5);
    SpiralOptions o;
    o.outer_radius = 3;
    o.pitch = 0.2;
    o.points.rule = CutterPointRule::kEqualAngle;
    o.points.points_per_revolution = 50;
    CompensationOptions c;
    c.tool.nose_radius = 0.5;
    ToolCheckOptions checks;
    checks.outer_radius = 3;
    MotionOptions motion;
    motion.spindle_rpm = 20;
    const std::string path = dir.file("job.iso-lathe-xzc.nc");
    AxisCollector expected;
    {
      PostProgram program(*iso, m, {"job", 20, 0}, path);
      struct Tee final : AxisSink {
        AxisSink *a, *b;
        void write(std::span<const AxisRecord> chunk) override {
          a->write(chunk);
          b->write(chunk);
        }
      } tee;
      tee.a = &program;
      tee.b = &expected;
      AxisMapper mapper(m, motion, tee);
      ToolCompensator compensator(asphere, c, checks, mapper);
      plan_spiral(asphere, BaseSurface::plane(3), o, compensator);
      program.finish();
    }
    const auto blocks = parse_nc(test::read_file(path), path);
    // The motion blocks are the G1 lines after G93, one per record after the first.
    std::vector<const NcBlock*> moves;
    bool inverse_time = false;
    for (const NcBlock& b : blocks) {
      for (const NcWord& w : b.words)
        if (w.letter == 'G' && w.value == 93) inverse_time = true;
      if (inverse_time && !b.words.empty() && b.words[0].letter == 'G' && b.words[0].value == 1)
        moves.push_back(&b);
    }
    REQUIRE(moves.size() == expected.records.size() - 1);
    for (std::size_t k = 0; k < moves.size(); ++k) {
      const AxisRecord& r = expected.records[k + 1];
      std::map<char, double> v;
      for (const NcWord& w : moves[k]->words) v[w.letter] = w.value;
      CHECK(std::abs(v['X'] - r.x) <= 0.5e-6 + 1e-12);
      CHECK(std::abs(v['Z'] - r.z) <= 0.5e-6 + 1e-12);
      CHECK(std::abs(v['C'] - r.c) <= 0.5e-5 + 1e-12);
      // F is 1 / (block time in minutes): 50 blocks per revolution at 20 rpm.
      CHECK(v['F'] == doctest::Approx(20 * 50).epsilon(1e-9));
    }
  }

  TEST_CASE("ncdiff: reformatted and re-commented is the same, a moved axis word is not") {
    const std::string a = "%\n(program)\nG21 G18\nG1 X1.000000 Z-0.500000 C10.0 F100\nG1 X0.9 Z-0.4\nM2\n";
    const std::string b = "%\nG18 G21 ; units\nG01 Z-0.5 X1 C10 F100.0 (same)\n\nN20 G1 X0.900000 Z-0.400000\nM02\n";
    const auto r = nc_diff(parse_nc(a, "a.nc"), "a.nc", parse_nc(b, "b.nc"), "b.nc");
    CHECK(r.same);
    const std::string moved = "%\nG21 G18\nG1 X1.000000 Z-0.500000 C10.0 F100\nG1 X0.9001 Z-0.4\nM2\n";
    const auto d = nc_diff(parse_nc(a, "a.nc"), "a.nc", parse_nc(moved, "c.nc"), "c.nc");
    CHECK_FALSE(d.same);
    CHECK(d.first_difference.find("a.nc:5 vs c.nc:4: X 0.9 ≠ 0.9001") == 0);
    CHECK(d.largest['X' - 'A'] == doctest::Approx(1e-4).epsilon(1e-6));
    CHECK_THROWS_WITH_AS(parse_nc("hello, world\n", "t.txt"), doctest::Contains("t.txt:1:"),
                         InputError);
  }
}
