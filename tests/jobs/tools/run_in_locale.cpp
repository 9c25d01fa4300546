// Runs a job with its simulation, every output on, in a given locale: the process's C
// locale (printf, strtod) and the global C++ one (streams) both set, as a host program
// that calls setlocale(LC_ALL, "") would have them. locale_test.sh compares the files
// with those written in the "C" locale.
// usage: run_in_locale <locale> <job.yaml> <output folder>
// Prints what printf makes of 1.5 in that locale (the test checks the locale took hold);
// exit 77 when the locale is not there.
#include <clocale>
#include <cstdio>
#include <exception>
#include <locale>

#include "freeturn/freeturn.hpp"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: run_in_locale <locale> <job.yaml> <output folder>\n");
    return 2;
  }
  if (!std::setlocale(LC_ALL, argv[1])) {
    std::fprintf(stderr, "run_in_locale: the locale %s is not installed\n", argv[1]);
    return 77;
  }
  try {
    std::locale::global(std::locale(argv[1]));
    std::printf("%.2f\n", 1.5);
    const freeturn::Job job = freeturn::load_job(argv[2]);
    freeturn::RunOptions options;
    options.output_dir = argv[3];
    freeturn::simulate_job(job, freeturn::SimulationOptions{}, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "run_in_locale: %s\n", e.what());
    return 1;
  }
  return 0;
}
