// NC writing throughput: megabytes of program text per second for a 10-million-point path
// through each post-processor plugin (host mapping excluded: synthetic axis records of a
// spiral, in chunks of 4096), written to a file under /tmp.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "freeturn/job/machine_yaml.hpp"
#include "freeturn/post/post_program.hpp"

namespace {

void run(benchmark::State& state, const char* machine_name) {
  const freeturn::MachineDescription m =
      freeturn::load_machine(std::string(FREETURN_MACHINE_DIR) + "/" + machine_name + ".yaml");
  const auto plugin = freeturn::PostPlugin::load_file(std::string(FREETURN_PLUGIN_DIR) +
                                                      "/libfreeturn_post_" + m.plugin + ".so");
  const long total = state.range(0);
  std::vector<freeturn::AxisRecord> chunk(4096);
  const std::string path = (std::filesystem::temp_directory_path() / "freeturn_bench.nc").string();
  // The synthetic spiral repeats every 1000 points: its sines come from a table, so that
  // the time measured is the posting's, not libm's.
  constexpr int kPerTurn = 1000;
  std::vector<double> z_of(kPerTurn), b_of(kPerTurn), c_of(kPerTurn);
  for (int k = 0; k < kPerTurn; ++k) {
    const double theta = k * 2 * M_PI / kPerTurn;
    z_of[k] = 0.01 * std::sin(theta * 3);
    b_of[k] = 0.5 * std::sin(theta);
    c_of[k] = std::fmod(k * 0.36, 360.0);
  }
  double bytes = 0;
  for (auto _ : state) {
    {
      // Z stays within ±0.01 mm: the clearance base above it, on the side Z's sign points to.
      const int away = static_cast<int>(m.spec(freeturn::Axis::kZ).sign);
      freeturn::PostProgram program(*plugin, m, {"bench", 100, 0, -1, -1, 0.02 * away, away}, path);
      for (long done = 0; done < total; done += static_cast<long>(chunk.size())) {
        for (std::size_t k = 0; k < chunk.size(); ++k) {
          const long i = done + static_cast<long>(k);
          const std::size_t turn = static_cast<std::size_t>(i % kPerTurn);
          chunk[k] = {10 - static_cast<double>(i) * 1e-6, z_of[turn], c_of[turn], b_of[turn],
                      i == 0 ? 0.0 : 0.0006};
        }
        program.write(chunk);
      }
      // Moore splits long programs into child files: count them all.
      for (const std::string& written : program.finish()) {
        bytes += static_cast<double>(std::filesystem::file_size(written));
        std::filesystem::remove(written);
      }
    }
  }
  state.counters["MB/s"] = benchmark::Counter(bytes / 1e6, benchmark::Counter::kIsRate);
  state.counters["points"] = static_cast<double>(total);
}

void BM_Post_Iso(benchmark::State& state) { run(state, "iso-lathe-xzc"); }
void BM_Post_Moore(benchmark::State& state) { run(state, "moore-nanotech-250upl"); }
void BM_Post_Precitech(benchmark::State& state) { run(state, "precitech-nanoform-250"); }

}  // namespace

BENCHMARK(BM_Post_Iso)->Arg(10'000'000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Post_Moore)->Arg(10'000'000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_Post_Precitech)->Arg(10'000'000)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
