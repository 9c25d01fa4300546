#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "freeturn/job/job.hpp"

using namespace freeturn;

TEST_SUITE("job") {
  TEST_CASE("the compensation example reads its Zygo file and finds the pose and error it was made with") {
    // configs/data/make_measured_compound_eye.py: decentre (12, −8) µm, tilt 5e-5 rad about x,
    // clocking 0.3°, astigmatism Z6 0.25 µm and trefoil Z9 0.15 µm, 1 nm noise.
    const Job job = load_job(FREETURN_SOURCE_DIR "/configs/jobs/compound_eye_compensated.yaml");
    REQUIRE(job.compensation.size() == 1);
    const MeasuredPart& part = job.compensation[0];
    const Registration& r = part.registration;
    CHECK(part.format == "zygo_xyz");
    CHECK(part.gain == 0.8);
    CHECK(part.invalid > 0);
    CHECK(std::abs(r.decentre_x - 0.012) < 0.5e-3);
    CHECK(std::abs(r.decentre_y + 0.008) < 0.5e-3);
    CHECK(std::abs(r.tilt_x - 5e-5) < 1e-6);
    CHECK(std::abs(r.tilt_y) < 1e-6);
    CHECK(std::abs(r.clocking - 0.3 * std::numbers::pi / 180) < 0.01 * std::numbers::pi / 180);
    CHECK(r.zernike[5] == doctest::Approx(0.25e-3).epsilon(0.01));
    CHECK(r.zernike[8] == doctest::Approx(0.15e-3).epsilon(0.01));
    CHECK(r.fit_rms < 1.5e-6);
    // The job cuts the design less 0.8 of that: the difference at a point off the axis.
    CHECK(job.surface->type() == std::string("compound_eye"));
  }
}
