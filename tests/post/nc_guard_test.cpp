#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "freeturn/core/error.hpp"
#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/post/nc_guard.hpp"
#include "freeturn/post/post_program.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

const std::string kPlugins = FREETURN_PLUGIN_DIR;
const std::string kMachines = FREETURN_MACHINE_DIR;

// X ∈ [−100, 100], Z ∈ [−50, 50] at 6 decimals, C accumulating (iso-lathe-xzc).
MachineDescription lathe() { return load_machine(kMachines + "/iso-lathe-xzc.yaml"); }

std::string refusal_of(NcGuard& guard, const std::string& text) {
  guard.select_file(0, "p.nc");
  guard.feed(text);
  guard.end_files();
  return guard.reason();
}

// The same with a fresh guard for machine `m`.
std::string refusal_of(const MachineDescription& m, const std::string& text) {
  NcGuard guard(m);
  return refusal_of(guard, text);
}

// What the guard on the lathe says of `text` ("" where it passes).
std::string refused(const std::string& text) {
  static const MachineDescription m = lathe();
  return refusal_of(m, text);
}

long files_in(const std::string& folder) {
  return std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator());
}

}  // namespace

TEST_SUITE("plugins") {
  TEST_CASE("the NC guard refuses every record no machine may get, before the plugin sees it") {
    const auto iso = PostPlugin::load_file(kPlugins + "/libfreeturn_post_iso.so");
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    struct Bad {
      AxisRecord record;
      const char* says;
    };
    for (const Bad& bad : {Bad{{nan, 0, 0, 0, 0.01}, "X = nan is not a finite number"},
                           Bad{{1, inf, 0, 0, 0.01}, "Z = inf is not a finite number"},
                           Bad{{1, 0, -inf, 0, 0.01}, "C = -inf is not a finite number"},
                           Bad{{100.001, 0, 0, 0, 0.01}, "X = 100.001 is outside its travel"},
                           Bad{{1, -50.01, 0, 0, 0.01}, "Z = -50.01 is outside its travel"},
                           Bad{{1, 0, 0, 0, nan}, "block time nan s is not a finite duration"},
                           Bad{{1, 0, 0, 0, -1}, "block time -1 s"},
                           Bad{{1, 1.000001, 0, 0, 0.01}, "Z 1.000001 rises past the clearance base 1 "}}) {
      test::TempDir dir;
      {
        PostProgram program(*iso, lathe(), {"job", 100, 0, -1, -1, 1.0, 1}, dir.file("job.nc"));
        const AxisRecord good[] = {{1, 0, 0, 0, 0}, {1.5, 0.1, 10, 0, 0.01}};
        program.write(good);
        const AxisRecord records[] = {bad.record};
        CAPTURE(bad.says);
        CHECK_THROWS_WITH_AS(program.write(records), doctest::Contains(bad.says), InputError);
        CHECK_THROWS_WITH_AS(program.write(records), doctest::Contains("block 3"), InputError);
      }
      CHECK(files_in(dir.path()) == 0);  // abandoned: no NC file, no temporary
    }
  }

  TEST_CASE("the NC guard reads back what a plugin wrote: finite, whole numbers inside the travel") {
    MachineDescription m = lathe();
    m.c_wrapped = true;  // C then within [0, 360]
    const auto refused = [&](const std::string& text) { return refusal_of(m, text); };
    CHECK(refused("%\nG21 G18\nG1 X1.000000 Z-2.5 C359.9999\nM30\n%\n").empty());
    CHECK(refused("G1 X100.0000004 Z0\n").empty());  // within half a unit of 6 decimals
    CHECK(refused("G1 X100.000001 Z0\n") == "p.nc:1: X100.000001 is outside the machine's range [-100.0000005, 100.0000005]");
    CHECK(refused("G1 X1\nG1 Xnan Z0\n") == "p.nc:2: a number that is not finite: G1 Xnan Z0");
    CHECK(refused("G1 X-inf\n").find("not finite") != std::string::npos);
    CHECK(refused("G1 X1.2.3\n") == "p.nc:1: X1.2.3 is not a number");
    CHECK(refused("G1 C360.5\n").find("C360.5 is outside") != std::string::npos);
    // At the bounds, where the integer part alone cannot settle it (half a unit of C's 5
    // decimals and X's 6 beyond each).
    CHECK(refused("G1 C360.000004 X-99.9999999 Z49.5\nG1 C-0.000004 X100.0000005\n").empty());
    CHECK(refused("G1 C360.000006\n").find("C360.000006 is outside") != std::string::npos);
    CHECK(refused("G1 C-0.000006\n").find("C-0.000006 is outside") != std::string::npos);
    CHECK(refused("G1 X-100.0000006\n").find("X-100.0000006 is outside") != std::string::npos);
    CHECK(refused("G1 Z00050.0000006\n").find("Z00050.0000006 is outside") != std::string::npos);
    CHECK(refused("G1 Z60 (a comment with X999 and nan)\n").find("Z60 is outside") != std::string::npos);
    CHECK(refused("G1 Z1 ; X999 nan after the semicolon\n").empty());
    // Out of the work frame: machine coordinates and presets.
    CHECK(refused("G53 Z-180.\nG92 C0\n").empty());
    // A reference return passes first through its axis words' point, in the work frame
    // (LinuxCNC's G28 and G30): before December 2026 G28 X500 passed.
    CHECK(refused("G28 X500\n") ==
          "p.nc:1: X500 is outside the machine's range [-100.0000005, 100.0000005]");
    CHECK(refused("G28 X0 Z0\nG30\n").empty());
    CHECK(refused("G53 Z-inf\n").find("not finite") != std::string::npos);
    // A last line without its newline is read too; each file keeps its own line count.
    NcGuard guard(m);
    guard.select_file(0, "main.nc");
    guard.feed("G1 X1\nG1 X2\n");
    guard.select_file(1, "child.nc");
    guard.feed("G1 X1\n");
    guard.select_file(0, "");
    guard.feed("G1 X3\nG1 X200");
    CHECK(guard.ok());
    guard.end_files();
    CHECK(guard.reason() == "main.nc:4: X200 is outside the machine's range [-100.0000005, 100.0000005]");
  }

  TEST_CASE("the NC guard refuses bytes no controller should get and words without their number") {
    // What an overrun formatter left after F: bytes of memory, in code or in a comment.
    CHECK(refused(std::string("G93 F\x01\x9c\n")) == "p.nc:1: byte 0x01 at column 6 is not printable ASCII");
    CHECK(refused(std::string("G1 X1 (\xc3\xa9)\n")) == "p.nc:1: byte 0xC3 at column 8 is not printable ASCII");
    CHECK(refused(std::string("G1 X1\0\n", 7)).find("byte 0x00 at column 6") != std::string::npos);
    // A line longer than a controller's buffer (LinuxCNC: 255 characters).
    CHECK(refused("(" + std::string(253, 'a') + ")\nG1 X1\n").empty());
    CHECK(refused("(" + std::string(253, 'a') + ")\r\n").empty());
    CHECK(refused("G1 X1\n(" + std::string(254, 'a') + ")\n") ==
          "p.nc:2: a line of 256 characters, longer than the 255 a controller reads: (" +
              std::string(39, 'a') + "…");
    // An axis or feed letter standing alone, or before a letter that is no number.
    CHECK(refused("G93 F\n") == "p.nc:1: F without a number after it: G93 F");
    CHECK(refused("G1 X Z1\n") == "p.nc:1: X without a number after it: G1 X Z1");
    CHECK(refused("G1 C@\n").find("C without a number") != std::string::npos);
    // Keywords whose letters are word letters are not words.
    CHECK(refused("G1 X1 Z1\nM30\nEXEC\n").empty());
    CHECK(refused("G1 X1.5 F200.\n").empty());
    // F reading 0 in any form: a feed or an (inverse) block time the controller cannot run.
    CHECK(refused("G1 X1 F0.000000\n") ==
          "p.nc:1: F0.000000 is 0: a feed or block time the controller cannot run");
    CHECK(refused("G93 F0\n").find("F0 is 0") != std::string::npos);
    CHECK(refused("G01 F-0.000\n").find("F-0.000 is 0") != std::string::npos);
    CHECK(refused("G01 F.0\n").find("F.0 is 0") != std::string::npos);
    CHECK(refused("G1 X1 F0.000001\nG93 F100.000\n").empty());
  }

  TEST_CASE("the NC guard refuses words after the program's end: the controller never runs them") {
    // A header that carries M30 ends the program before the cut the report describes.
    CHECK(refused("%\nG71\nM30\nM03 S20\nG1 X1 Z1\n") ==
          "p.nc:4: words after the program's end (M30 on line 3), which the controller never "
          "runs: M03 S20");
    CHECK(refused("G1 X1\nM02\nG1 X2\n").find("(M02 on line 2)") != std::string::npos);
    CHECK(refused("G1 X1\nm2 (end)\nG1 X2\n").find("(M2 on line 2)") != std::string::npos);
    CHECK(refused("G1 X1\nM099\nG1 X2\n").find("(M099 on line 2)") != std::string::npos);
    // What may follow an end: nothing a controller runs (a tape mark, comments, blank lines).
    CHECK(refused("G1 X1\nM30\n%\n(done)\n\n; X5\n").empty());
    CHECK(refused("G1 X1 M30\n").empty());  // its own line's words run
    // Codes that only look like ends: M3, M300, M29, M2.5 (no integer), M98 (a call).
    CHECK(refused("M3\nM300\nM29\nM2.5\nM98(child.nc)\nG1 X1\n").empty());
    // Each file ends on its own: a child's M99 does not end the main program.
    NcGuard guard(lathe());
    guard.select_file(0, "main.nc");
    guard.feed("G1 X1\nM98(child.nc)\n");
    guard.select_file(1, "child.nc");
    guard.feed("G1 X1\nM99\n");
    guard.select_file(0, "");
    guard.feed("G1 X2\nM30\n");
    guard.end_files();
    CHECK(guard.ok());
    guard.select_file(1, "");
    guard.feed("G1 X3\n");
    CHECK(guard.reason() ==
          "child.nc:3: words after the program's end (M99 on line 2), which the controller never "
          "runs: G1 X3");
  }

  TEST_CASE(
      "the NC guard reads '%' as the tape's marks: first it starts the program, later it ends it") {
    // RS-274 (LinuxCNC's reader, Fanuc's): a line of '%' alone that is the file's first
    // line with anything on it starts the program; a later one ends it, and nothing after
    // it is run.
    CHECK(refused("%\nG1 X1\nM2\n%\n").empty());
    CHECK(refused("\n  % \r\nG1 X1\nM2\n%\n").empty());  // blank lines before, spaces about it
    CHECK(refused("G1 X1\n%\n").empty());                // an end with nothing after it
    CHECK(refused("(a comment)\n%\nG1 X1\n") ==
          "p.nc:3: words after the program's end (% on line 2), which the controller never runs: "
          "G1 X1");
    CHECK(refused("%\nG1 X1\n%\nG1 X2\n").find("(% on line 3)") != std::string::npos);
    // A '%' that is not a mark: among words, or with words after it.
    CHECK(refused("G1 X1 %\n").find("'%' inside a block") != std::string::npos);
    CHECK(refused("% G1 X1\n").find("'%' with words after it") != std::string::npos);
    // In a comment it is text.
    CHECK(refused("G1 X1 (50 %)\n; 10 %\n").empty());
  }

  TEST_CASE("the NC guard refuses two G codes of one modal group in a block, and a negative F") {
    CHECK(refused("G0 G1 X1\n") ==
          "p.nc:1: two G codes of RS-274's motion group in one block, which a controller refuses: "
          "G0 G1 X1");
    CHECK(refused("G93 G1 X1 G94 F2\n").find("RS-274's feed-rate mode group") != std::string::npos);
    CHECK(refused("G0 G90 G40 G18 G21 G94 G1.5 X1\n").empty());  // G1.5: no code of the table
    CHECK(refused("G93 G1 X1 F-0.25\n") == "p.nc:1: F-0.25 is negative: no feed or block time is");
  }

  TEST_CASE("the NC guard refuses axis words under a mode they were not written for") {
    // A machine YAML's header that left G91 (or inches, cutter compensation, diameter mode,
    // an arc) in effect turned every absolute millimetre of the cut into something else,
    // and passed (December 2026).
    CHECK(refused("G71 G91\nG1 X1 Z1\n") ==
          "p.nc:2: an axis word under G91 (incremental distances, line 1), where the program's "
          "words assume absolute millimetres in radius mode, no cutter compensation, straight "
          "moves and feeds by time (G93 or G94): G1 X1 Z1");
    CHECK(refused("G95\nG1 X1\n").find("under G95 (feed per revolution, line 1)") !=
          std::string::npos);
    CHECK(refused("G95\nG94 X1\nG93 X2 F1\n").empty());
    CHECK(refused("G70\nG1 X1\n").find("under G70 (inches, line 1)") != std::string::npos);
    CHECK(refused("g20\nG1 X1\n").find("under g20 (inches, line 1)") != std::string::npos);
    CHECK(refused("G42\nG1 X1\n").find("under G42 (cutter-radius compensation") !=
          std::string::npos);
    CHECK(refused("G41.1 D1\nG1 X1\n").find("under G41.1 (cutter-radius") != std::string::npos);
    CHECK(refused("G7\nG1 X1\n").find("under G7 (diameter mode") != std::string::npos);
    CHECK(refused("G81 R1\nX1 Z1\n").find("under G81 (a motion mode that is no straight move") !=
          std::string::npos);
    CHECK(refused("G02\nX1\n").find("under G02") != std::string::npos);
    CHECK(refused("G80\nX1\n").find("under G80") != std::string::npos);
    // On the line itself, whatever the order of its words (a controller sets the modes first).
    CHECK(refused("G91 X1\n").find("under G91 (incremental distances, line 1)") !=
          std::string::npos);
    CHECK(refused("X1 G91\n").find("under G91") != std::string::npos);
    // A child is called in the caller's modes.
    CHECK(refused("G91\nM98(child.nc)\n").find("p.nc:2: a call of a child program under G91") !=
          std::string::npos);
    // Modes restored before the words, or left where no axis word follows, are fine; so are
    // machine coordinates under G91 (always absolute) and a reference return through
    // increments of 0 (the idiom G91 G28 X0 Z0, then G90).
    CHECK(refused("G91\nG90\nG1 X1\nG20\nG21 G41\nG40 X2\nG7\nG8\nG81\nG1 X3\nM30\n").empty());
    CHECK(refused("G71 G01 G18 G40 G63 G90 G94 G54\nG91\nG53 Z-180.\nG28 X0 Z0\nG90 X1\n").empty());
    CHECK(refused("G91 G28 X1\n").find("under G91") != std::string::npos);
    CHECK(refused("G91\nM30\n").empty());
    // Each file keeps its own modes: a child opens as its caller stood at the call, which
    // the call's own line checks.
    NcGuard guard(lathe());
    guard.select_file(0, "main.nc");
    guard.feed("G91\n");
    guard.select_file(1, "child.nc");
    guard.feed("G1 X1\n");
    CHECK(guard.ok());
    // A child that leaves a mode leaves it for its caller too.
    NcGuard returns(lathe());
    returns.select_file(0, "main.nc");
    returns.feed("G1 X1\nM98(child.nc)\nG1 X2\n");
    returns.select_file(1, "child.nc");
    returns.feed("G1 X1\nG91\nM99\n");
    returns.end_files();
    CHECK(returns.reason() ==
          "child.nc:3: the child returns to its caller under G91 (incremental distances, line "
          "2), where the caller's words assume absolute millimetres in radius mode, no cutter "
          "compensation, straight moves and feeds by time (G93 or G94)");
    NcGuard restores(lathe());
    restores.select_file(1, "child.nc");
    restores.feed("G91\nG90 G1 X1\nM99\n");
    restores.end_files();
    CHECK(restores.ok());
  }

  TEST_CASE("the NC guard refuses a feed per minute that asks an axis for more than its velocity") {
    // The lathe's X and Z go at most 50 mm/s (3000 mm/min), C 3600 °/s. A Moore with
    // approach_feed 9000 had plunged at 150 mm/s on a 25 mm/s Z, and passed (December 2026).
    CHECK(refused("G94 G1 Z1 F3000\n").empty());
    CHECK(refused("G94 G1 Z1 F3000.1\n") ==
          "p.nc:1: F3000.1 a minute (G94) moves Z at 50.001666666666665 mm/s, beyond its "
          "max_velocity 50 in the machine file: G94 G1 Z1 F3000.1");
    // The feed is modal, and so is G94, a controller's power-on default; G93's F is a time.
    CHECK(refused("G1 X1 F6000\n").find("moves X at 100 mm/s") != std::string::npos);
    CHECK(refused("G93 G1 X1 F6000\nX2 F7000\n").empty());
    CHECK(refused("G93 G1 X1 F6000\nG94\nX2\n").find("p.nc:3: F6000 a minute") !=
          std::string::npos);
    // Rapids go at the machine's own rate, machine coordinates are not the work's move.
    CHECK(refused("G94 F6000\nG0 X1\nG53 G1 Z-1\n").empty());
    // A rotary axis turning alone goes at the feed in °/min.
    CHECK(refused("G94 G1 C10 F300000\n")
              .find("moves C at 5000 deg/s, beyond its max_velocity 3600") != std::string::npos);
  }

  TEST_CASE("the NC guard refuses a rotary axis turning beside a linear one in a feed per minute") {
    // The turn takes the linear move's time: 10° beside a 1 µm move of X at F2000 is C at
    // 333 333 °/s, and where X was need not be written. The Moore's approach had turned B
    // beside X so, from wherever the header left X (December 2026).
    CHECK(refused("G94 G1 X1 C10 F2000\n") ==
          "p.nc:1: C10 turns from an angle no earlier line of the file gives together with a "
          "linear axis in a feed per minute (G94): its speed would follow from the linear "
          "move's length, which the program does not settle; turn it on a line of its own: "
          "G94 G1 X1 C10 F2000");
    CHECK(refused("G94 G1 C10 F2000\nX1 C11\n").find("p.nc:2: C11 turns from C10 together") !=
          std::string::npos);
    // Turned first on its own line, it stands still beside X, however the angle is written.
    CHECK(refused("G94 G1 C10 F2000\nX1 C10\nX2 C10.000 Z1\nX3 C+10.\n").empty());
    CHECK(refused("G92 C0\nG94 G1 X1 C0 F2000\n").empty());  // G92: C is now at 0
    // Timed blocks (G93), rapids, and moves without a feed are not timed by a feed per minute.
    CHECK(refused("G93 G1 X1 C10 F2000\nG0 X2 C20\n").empty());
    CHECK(refused("G1 X1 C10\n").empty());
    // Outside the work frame, or after a file switch, the angle is no longer known.
    CHECK(refused("G94 G1 C10 F2000\nG53 C10\nX1 C10\n").find("p.nc:3: C10 turns from an angle") !=
          std::string::npos);
    CHECK(refused("G94 G1 C10 F2000\nG28 C10\nX1 C10\n").find("p.nc:3: C10 turns") !=
          std::string::npos);
    NcGuard switched(lathe());
    switched.select_file(0, "main.nc");
    switched.feed("G94 G1 C10 F2000\nM98(child.nc)\n");
    switched.select_file(1, "child.nc");
    switched.feed("G93 X2 C30 F5\nM99\n");
    switched.select_file(0, "main.nc");
    switched.feed("G94 X1 C10\n");
    switched.end_files();
    CHECK(switched.reason().find("main.nc:3: C10 turns from an angle no earlier") == 0);
  }

  TEST_CASE("the NC guard refuses a preset of an axis the program positions") {
    CHECK(refused("G92 X5.0 C0\n") ==
          "p.nc:1: X in a preset (G10, G52, G92) moves the frame the program's positions are "
          "given in (a preset of C alone sets the spindle's zero): G92 X5.0 C0");
    CHECK(refused("G52 Z0\n").find("Z in a preset") != std::string::npos);
    CHECK(refused("G10 L20 P1 X0\n").find("X in a preset") != std::string::npos);
    // The Moore's own header and footer: C's zero, and G52 with no axis word.
    CHECK(refused("G09 C0.0\nG92 C0.0\nG52\nG92 C999\n").empty());
  }

  TEST_CASE(
      "the NC guard refuses a comment a controller stops on: nested, unclosed, or a lone ')'") {
    // A header "G71 (note" put the rest of its block in a comment: G01 G18 G90 … were never
    // read, and the guard passed it (December 2026).
    CHECK(refused("G71 (note G01 G18 G90\nG1 X1\n") ==
          "p.nc:1: a comment '(' without ')' on its line: a controller stops there (column 5): "
          "G71 (note G01 G18 G90");
    CHECK(refused("G1 X1 (a (b) c)\n") ==
          "p.nc:1: '(' inside a comment: controllers do not nest comments (column 10): "
          "G1 X1 (a (b) c)");
    CHECK(refused("G71 ) G18\n") == "p.nc:1: ')' outside a comment (column 5): G71 ) G18");
    CHECK(refused("(a) ) X1\n").find("')' outside a comment (column 5)") != std::string::npos);
    CHECK(refused("% (start\nG1 X1\n").find("without ')'") != std::string::npos);
    // After a ';' every byte is comment text, parentheses too (the Precitech's header).
    CHECK(refused("G1 X1 ; PVT on (edit for your UPx\n(a)(b) G1 X2 (c;)\nM98(child.nc)\n").empty());
  }
}
