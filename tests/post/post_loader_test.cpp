#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "freeturn/core/error.hpp"
#include "freeturn/io/nc_program.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/machine/axis_mapper.hpp"
#include "freeturn/path/spiral.hpp"
#include "freeturn/post/post_program.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "freeturn/tool/clearance.hpp"
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
                         doctest::Contains("post-processor ABI version 99; this freeturn needs version 3"),
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
                         doctest::Contains("refuses its settings: this dialect needs a setting 'program_number'"),
                         InputError);
    // Nothing was left behind.
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 0);
    unsetenv("FREETURN_PLUGIN_PATH");
  }

  TEST_CASE("every post: its program parses back to the axis values at the declared decimals") {
    struct Case {
      const char* machine;
      bool chord;  // chord-controlled points (varying block times) or equal angles
    };
    for (const Case& c : {Case{"iso-lathe-xzc", true}, Case{"iso-lathe-xzcb", true},
                          Case{"moore-nanotech-250upl", true}, Case{"moore-nanotech-350fg-b", true},
                          Case{"precitech-nanoform-250", false}}) {
      CAPTURE(c.machine);
      MachineDescription m = load_machine(kMachines + "/" + c.machine + ".yaml");
      // Small child files, so that the Moore main program calls several.
      const std::size_t child = m.dialect_settings.find("child_blocks: 500000");
      if (child != std::string::npos) m.dialect_settings.replace(child, 20, "child_blocks: 300");
      const auto plugin = PostPlugin::load_file(kPlugins + "/libfreeturn_post_" + m.plugin + ".so");
      test::TempDir dir;
      const EvenAsphere asphere(1 / 30.0, -0.5);
      SpiralOptions o;
      o.outer_radius = 3;
      o.pitch = 0.2;
      o.points.rule = c.chord ? CutterPointRule::kChordError : CutterPointRule::kEqualAngle;
      o.points.tolerance = 1e-4;
      o.points.points_per_revolution = 50;
      CompensationOptions comp;
      comp.tool.nose_radius = 0.5;
      if (m.has(Axis::kB)) {
        comp.b_mode = BMode::kFollow;
        comp.pivot_distance = m.pivot_distance;
      }
      ToolCheckOptions checks;
      checks.outer_radius = 3;
      MotionOptions motion;
      motion.spindle_rpm = 20;
      const std::string path = dir.file(std::string("job.") + c.machine + ".nc");
      AxisCollector expected;
      std::vector<std::string> written;
      // The sag rises to 3²/(30 (1 + √(1 − 0.5·9/900))) = 0.150188 mm at r = 3.
      const double sag_top = 9 / (30 * (1 + std::sqrt(1 - 0.5 * 9 / 900)));
      const double ceiling = program_z_ceiling(asphere, 0, 3, comp, 0);
      const double point = comp.pivot_distance > 0 ? comp.pivot_distance : 0;
      CHECK(ceiling == doctest::Approx(sag_top + 0.5 + point + kCeilingMargin).epsilon(1e-9));
      {
        PostProgram program(*plugin, m, {"job", 20, 0, -1, -1, ceiling, 1}, path);
        struct Tee final : AxisSink {
          AxisSink *a = nullptr, *b = nullptr;
          void write(std::span<const AxisRecord> chunk) override {
            a->write(chunk);
            b->write(chunk);
          }
        } tee;
        tee.a = &program;
        tee.b = &expected;
        AxisMapper mapper(m, motion, tee);
        ToolCompensator compensator(asphere, comp, checks, mapper);
        plan_spiral(asphere, BaseSurface::plane(3), o, compensator);
        written = program.finish();
      }
      // The main program with its child files spliced in where it calls them.
      std::vector<NcBlock> blocks;
      for (const NcBlock& b : parse_nc(test::read_file(path), path)) {
        bool call = false;
        for (const NcWord& w : b.words)
          if (!w.numeric && w.text.rfind("M98(", 0) == 0) {
            const std::string child_path = dir.file(w.text.substr(4, w.text.size() - 5));
            for (const NcBlock& cb : parse_nc(test::read_file(child_path), child_path))
              blocks.push_back(cb);
            call = true;
          }
        if (!call) blocks.push_back(b);
      }
      if (m.plugin == "moore") CHECK(written.size() > 2);
      // The last blocks with an X word are the records after the first, in order.
      std::vector<std::map<char, double>> moves;
      for (const NcBlock& b : blocks) {
        std::map<char, double> v;
        for (const NcWord& w : b.words)
          if (w.numeric) v[w.letter] = w.value;
        if (v.count('X')) moves.push_back(v);
      }
      const std::size_t n = expected.records.size() - 1;
      REQUIRE(moves.size() >= n);
      double worst[4] = {0, 0, 0, 0};
      for (std::size_t k = 0; k < n; ++k) {
        const AxisRecord& r = expected.records[k + 1];
        const auto& v = moves[moves.size() - n + k];
        worst[0] = std::max(worst[0], std::abs(v.at('X') - r.x));
        worst[1] = std::max(worst[1], std::abs(v.at('Z') - r.z));
        // C wrapped: a value just below 360 may be written as 0.
        worst[2] = std::max(worst[2], std::abs(std::remainder(v.at('C') - r.c, 360.0)));
        if (m.has(Axis::kB)) worst[3] = std::max(worst[3], std::abs(v.at('B') - r.b));
      }
      CHECK(worst[0] <= 0.5e-6 * (1 + 1e-9));
      CHECK(worst[1] <= 0.5e-6 * (1 + 1e-9));
      CHECK(worst[2] <= 0.5e-5 * (1 + 1e-9));
      CHECK(worst[3] <= 0.5e-5 * (1 + 1e-9));
      // The way in and out: every move that is not a record's runs at the clearance
      // height, `retract` (1 mm in these machines) above the highest record, or comes
      // straight down from it to the first record.
      if (m.plugin == "precitech") continue;  // its approach is the header template's
      double highest = -1e300;
      for (const AxisRecord& r : expected.records) highest = std::max(highest, r.z);
      CHECK(highest <= ceiling);
      int clear_moves = 0;
      double z = -1e300;  // modal
      for (std::size_t k = 0; k < blocks.size(); ++k) {
        std::map<char, double> v;
        bool home = false;
        for (const NcWord& w : blocks[k].words) {
          if (w.numeric) v[w.letter] = w.value;
          home = home || (w.numeric && w.letter == 'G' && w.value == 53);
        }
        if (home || (!v.count('Z') && !v.count('X'))) continue;
        if (v.count('Z')) z = v.at('Z');
        if (z <= highest + 1e-9) continue;
        CHECK(z >= ceiling + 1.0 - 1e-9);
        ++clear_moves;
      }
      CHECK(clear_moves >= 3);  // to the height, over the first record, and away at the end
    }
  }

  TEST_CASE("moore writes G93 F when its written text changes, not when the time's double does") {
    const MachineDescription m = load_machine(kMachines + "/moore-nanotech-250upl.yaml");
    const auto plugin = PostPlugin::load_file(kPlugins + "/libfreeturn_post_moore.so");
    test::TempDir dir;
    const std::string path = dir.file("times.nc");
    // Block times at the post's six decimals: 0.1333331 and 0.1333334 both read 0.133333,
    // 0.1333336 reads 0.133334, then 0.2 twice.
    const double times[] = {0, 0.1333331, 0.1333334, 0.1333336, 0.2, 0.2};
    {
      PostProgram program(*plugin, m, {"times", 20, 0, -1, -1, 1.0, 1}, path);
      std::vector<AxisRecord> r;
      for (int k = 0; k < 6; ++k) r.push_back({3.0 - 0.1 * k, 0.1, 10.0 * k, 0, times[k]});
      program.write(r);
      program.finish();
    }
    // The blocks are in the child point file the main program calls (M98(times_001.nc)).
    const std::string main_text = test::read_file(path);
    REQUIRE(main_text.find("M98(times_001.nc)") != std::string::npos);
    const std::string text = test::read_file(dir.file("times_001.nc"));
    std::vector<std::string> feeds;
    for (std::size_t at = text.find("G93 F"); at != std::string::npos; at = text.find("G93 F", at + 1))
      feeds.push_back(text.substr(at, text.find('\n', at) - at));
    CHECK(feeds == std::vector<std::string>{"G93 F0.133333", "G93 F0.133334", "G93 F0.200000"});
    // Each block still runs at its own time, as F is modal: the F in force before every
    // block with an X word after the approach, read back, is its time rounded.
    std::vector<double> in_force;
    double f = -1;
    for (const NcBlock& b : parse_nc(text, path)) {
      bool x = false, g93 = false;
      for (const NcWord& w : b.words) {
        if (w.numeric && w.letter == 'G' && w.value == 93) g93 = true;
        if (w.numeric && w.letter == 'F' && g93) f = w.value;
        if (w.numeric && w.letter == 'X') x = true;
      }
      if (x && f > 0) in_force.push_back(f);
    }
    REQUIRE(in_force.size() == 5);
    for (int k = 0; k < 5; ++k)
      CHECK(in_force[static_cast<std::size_t>(k)] == doctest::Approx(std::round(times[k + 1] * 1e6) / 1e6).epsilon(1e-12));
  }

  TEST_CASE("moore refuses a spindle speed its S word would print as 0") {
    const MachineDescription m = load_machine(kMachines + "/moore-nanotech-250upl.yaml");
    const auto plugin = PostPlugin::load_file(kPlugins + "/libfreeturn_post_moore.so");
    test::TempDir dir;
    const std::vector<AxisRecord> r = {{3.0, 0.1, 0.0, 0, 0}, {2.9, 0.1, 4.0, 0, 600}};
    const auto write_at = [&](double rpm) {
      const std::string path = dir.file("slow.nc");
      PostProgram program(*plugin, m, {"slow", rpm, 0, -1, -1, 1.0, 1}, path);
      program.write(r);
      program.finish();
      return test::read_file(path);
    };
    // S has three decimals: 0.0004 rpm would read S0.000, a stopped spindle; 0.0006 reads
    // S0.001, the least it can say.
    CHECK_THROWS_WITH_AS(write_at(0.0004), doctest::Contains("0.0004 rpm reads S0.000"),
                         InputError);
    CHECK(write_at(0.0006).find("M03 S0.001\n") != std::string::npos);
  }

  TEST_CASE(
      "a dialect's code settings carry only what a controller may get, refused at the setting") {
    test::TempDir dir;
    const auto refusal = [&](const std::string& machine, const std::string& plugin,
                             const std::string& from, const std::string& to) {
      MachineDescription m = load_machine(kMachines + "/" + machine + ".yaml");
      const std::size_t at = m.dialect_settings.find(from);
      REQUIRE(at != std::string::npos);
      m.dialect_settings.replace(at, from.size(), to);
      const auto post = PostPlugin::load_file(kPlugins + "/libfreeturn_post_" + plugin + ".so");
      try {
        PostProgram program(*post, m, {"job", 20, 1, -1, -1, 1.0, 1}, dir.file("p.nc"));
      } catch (const InputError& e) {
        return std::string(e.what());
      }
      return std::string("accepted");
    };
    // Moore writes its spindle word on the line of S: a second line there (a rapid to
    // Z-50, below the part) had gone to the controller as written.
    CHECK(refusal("moore-nanotech-250upl", "moore", "spindle: M03", "spindle: M03\\nG00 X0 Z-50")
              .find("moore-nanotech-250upl.yaml:15:12: post-processor 'moore'") !=
          std::string::npos);
    CHECK(refusal("moore-nanotech-250upl", "moore", "spindle: M03", "spindle: G00 X0")
              .find("dialect setting 'spindle' must be one of M03, M04, M3, M4, not 'G00 X0'") !=
          std::string::npos);
    CHECK(refusal("moore-nanotech-250upl", "moore", "spindle: M03", "spindle: M04") == "accepted");
    // A byte no controller may get, in a header: refused at the header, not at the program.
    const std::string bell = refusal("moore-nanotech-250upl", "moore", "T0101", "T0101\x07");
    CHECK(bell.find("moore-nanotech-250upl.yaml:13:11: post-processor 'moore'") !=
          std::string::npos);
    CHECK(bell.find("refuses its settings: dialect setting 'header' holds the byte 0x07") !=
          std::string::npos);
    CHECK(refusal("precitech-nanoform-250", "precitech", "; end of data", "; fin\xC3\xA9")
              .find("dialect setting 'footer' holds the byte 0xC3") != std::string::npos);
    // A footer's move in the work frame is not checked against the part: after the
    // retract, G00 X0 Z-0.5 went into its centre, and the program passed (December 2026).
    CHECK(refusal("moore-nanotech-250upl", "moore", "G53 Z-180.\\nM79",
                  "G00 X0 Z-0.5\\nG53 Z-180.\\nM79")
              .find("dialect setting 'footer' gives X or Z in the work frame ('G00 X0 Z-0.5')") !=
          std::string::npos);
    CHECK(refusal("precitech-nanoform-250", "precitech", "; PVT on", "g1 w-2 ; PVT on")
              .find("'header' gives X or Z in the work frame ('g1 w-2 ; PVT on (edit for your "
                    "UPx)')") != std::string::npos);
    // Nor does a reference return through increments of 0 (Fanuc's G28 U0 W0); through
    // work coordinates, or a real increment, it does.
    CHECK(refusal("moore-nanotech-250upl", "moore", "G53 Z-180.\\nM79",
                  "G28 U0 W0.\\nG53 Z-180.\\nM79") == "accepted");
    CHECK(refusal("moore-nanotech-250upl", "moore", "G53 Z-180.\\nM79",
                  "G28 X0 Z0\\nG53 Z-180.\\nM79")
              .find("gives X or Z in the work frame ('G28 X0 Z0')") != std::string::npos);
    CHECK(refusal("moore-nanotech-250upl", "moore", "G53 Z-180.\\nM79",
                  "G28 U0 W5\\nG53 Z-180.\\nM79")
              .find("gives X or Z in the work frame ('G28 U0 W5')") != std::string::npos);
    // Machine coordinates park; words in comments, B, Y and C, and keywords are no such move.
    CHECK(refusal("moore-nanotech-250upl", "moore", "G53 Z-180.\\nM79",
                  "G053 X-100 Z-180.\\n(X0 Z0) ; Z-1\\nY0 B0 C0\\nWHILE [1] DO1\\nM79") ==
          "accepted");
    // The time word is a letter of its own: Y, A or W would move an axis (W is Z's
    // increment on a lathe), S set the spindle's speed to each block's time.
    for (const char* letter : {"Y", "A", "U", "W", "S", "O"})
      CHECK(refusal("precitech-nanoform-250", "precitech", "; end of data",
                    std::string("; end of data\ntime_word: ") + letter)
                .find("time_word must be one capital letter that is no axis") != std::string::npos);
    CHECK(refusal("precitech-nanoform-250", "precitech", "; end of data",
                  "; end of data\ntime_word: T") == "accepted");
    // A header that ends the program: the controller would stop before the cut. Refused as
    // the header is written (line 8 of the main program: the title, then seven lines).
    const std::string ended =
        refusal("moore-nanotech-250upl", "moore", "G92 C0.0", "G92 C0.0\\nM30");
    CHECK(ended.find("p.nc:9: words after the program's end (M30 on line 8)") != std::string::npos);
    CHECK(std::filesystem::is_empty(dir.path()));
  }

  TEST_CASE("iso X-Z profile with feed per minute: G94 and the path feed, no G93") {
    const MachineDescription m = load_machine(kMachines + "/iso-lathe-xz.yaml");
    REQUIRE(m.feed_per_minute);
    const auto plugin = PostPlugin::load_file(kPlugins + "/libfreeturn_post_iso.so");
    test::TempDir dir;
    const std::string path = dir.file("profile.nc");
    {
      PostProgram program(*plugin, m, {"profile", 0, 2.5, -1, -1, 0.2, 1}, path);
      std::vector<AxisRecord> r = {{3, 0.2, 0, 0, 0}, {2, 0.1, 0, 0, 24}, {1, 0.05, 0, 0, 24}};
      program.write(r);
      program.finish();
    }
    const std::string text = test::read_file(path);
    CHECK(text.find("G93") == std::string::npos);
    CHECK(text.find("\nF2.500\n") != std::string::npos);
    CHECK(text.find("G1 X1.000000 Z0.050000\n") != std::string::npos);
    // And a machine that programs C cannot take feed per minute.
    test::TempDir machines;
    const std::string bad = machines.write(
        "m.yaml", "name: m\nplugin: iso\naxes: [{name: X}, {name: Z}, {name: C}]\nfeed_mode: per_minute\n");
    CHECK_THROWS_WITH_AS(load_machine(bad), doctest::Contains("m.yaml:4:12: feed_mode per_minute cannot time C-axis moves"),
                         InputError);
  }

  TEST_CASE("precitech refuses varying block times it cannot write") {
    const MachineDescription m = load_machine(kMachines + "/precitech-nanoform-250.yaml");
    const auto plugin = PostPlugin::load_file(kPlugins + "/libfreeturn_post_precitech.so");
    test::TempDir dir;
    PostProgram program(*plugin, m, {"job", 20, 0, -1, -1, 0, 1}, dir.file("p.nc"));
    std::vector<AxisRecord> r = {{1, 0, 0, 0, 0}, {0.9, 0, 10, 0, 0.1}, {0.8, 0, 20, 0, 0.2}};
    CHECK_THROWS_WITH_AS(program.write(r), doctest::Contains("block times vary"), InputError);
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
