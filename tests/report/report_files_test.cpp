#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "freeturn/io/output_set.hpp"
#include "freeturn/report/report_files.hpp"
#include "freeturn/surface/even_asphere.hpp"
#include "test_files.hpp"

using namespace freeturn;

namespace {

// A run's report made by hand: one pass, one warning with a place and one without, and a
// job text holding a Latin-1 byte (as a reader that let it through would pass it on).
RunReport sample_report() {
  RunReport r;
  r.job = "plate";
  r.job_file = "plate.yaml";
  r.job_text = "name: plate\n# f\xfcr die Werkstatt\n";
  r.version = "9.9.9";
  r.machine = "m";
  r.plugin = "libfreeturn_post_iso.so";
  r.parameters.strategy = "profile";
  r.parameters.points_rule = "chord";
  r.parameters.direction = "edge to centre";
  r.parameters.timing = "scheduled";
  r.parameters.outer_radius = 2;
  r.has_axis[0] = r.has_axis[1] = true;
  r.max_velocity[0] = 25;
  r.max_velocity[1] = std::numeric_limits<double>::infinity();  // no limit stated
  PassFigures& f = r.add_pass("finish", 0);
  f.points = 3;
  f.chord_max = 1.2345678901234567e-7;  // mm
  ReportWarning placed;
  placed.kind = "clearance";
  placed.severity = ReportWarning::Severity::kUnsafe;
  placed.pass = "finish";
  placed.message = "clearance: 1 points";
  placed.count = 1;
  placed.theta_deg = 359.5;
  placed.r_mm = 1.25;
  placed.x_mm = 1.25;
  placed.y_mm = -0.01;
  placed.value = 12.5;
  placed.limit = 10;
  placed.unit = "deg";
  ReportWarning bare;
  bare.kind = "slowed_blocks";
  bare.severity = ReportWarning::Severity::kNote;
  bare.message = "2 blocks slowed";
  r.warnings = {placed, bare};
  return r;
}

}  // namespace

TEST_SUITE("report") {
  TEST_CASE("report.json: schema version, structured warnings, nulls, exact numbers, UTF-8 always") {
    test::TempDir dir;
    const RunReport r = sample_report();
    const EvenAsphere flat(0, 0);
    OutputSet outputs;
    write_report(r, flat, dir.file("plate.report.json"), dir.file("plate.report.html"), outputs);
    outputs.commit();
    const std::string text = test::read_file(dir.file("plate.report.json"));
    // Strict UTF-8: nlohmann's parser refuses a stray byte. The Latin-1 ü is U+FFFD.
    const nlohmann::json j = nlohmann::json::parse(text);
    CHECK(j["schema_version"] == 1);
    CHECK(j["generator"]["version"] == "9.9.9");
    CHECK(j["job"]["yaml"] == "name: plate\n# f\xef\xbf\xbdr die Werkstatt\n");
    CHECK(j["verdict"]["status"] == "UNSAFE");
    CHECK(j["verdict"]["reasons"] == nlohmann::json::array({"finish: clearance: 1 points"}));
    const auto& w = j["warnings"];
    REQUIRE(w.size() == 2);
    CHECK(w[0]["kind"] == "clearance");
    CHECK(w[0]["severity"] == "unsafe");
    CHECK(w[0]["theta_deg"] == 359.5);
    CHECK(w[0]["value"] == 12.5);
    CHECK(w[0]["limit"] == 10.0);
    CHECK(w[0]["unit"] == "deg");
    // What is not known is null, not a number and not absent.
    CHECK(w[1]["pass"].is_null());
    CHECK(w[1]["theta_deg"].is_null());
    CHECK(w[1]["r_mm"].is_null());
    CHECK(w[1]["unit"].is_null());
    CHECK(w[1]["severity"] == "note");
    // Numbers read back as the doubles written (shortest round-trip text).
    CHECK(j["passes"][0]["chord_error_nm"]["max"].get<double>() == 1.2345678901234567e-7 * 1e6);
    // A limit the machine does not state is null; an axis it does not have is absent.
    CHECK(j["machine"]["max_velocity_per_s"]["X"] == 25.0);
    CHECK(j["machine"]["max_velocity_per_s"]["Z"].is_null());
    CHECK_FALSE(j["machine"]["max_velocity_per_s"].contains("C"));
    // The page says the same: UNSAFE with the reason, the Latin-1 byte not passed on raw.
    const std::string html = test::read_file(dir.file("plate.report.html"));
    CHECK(html.find("UNSAFE") != std::string::npos);
    CHECK(html.find("finish: clearance: 1 points") != std::string::npos);
    CHECK(html.find("<script") == std::string::npos);
    CHECK(html.find('\xfc') == std::string::npos);
    CHECK(html.find("f\xef\xbf\xbdr die Werkstatt") != std::string::npos);
  }
}
