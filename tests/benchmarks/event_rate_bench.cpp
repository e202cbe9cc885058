// Fired events per wall second of the event fidelity (SystemC pixel modules, ideal bus):
// the aloha preset on a letter, and a QCIF (176x144) array under bright uniform light.
#include <benchmark/benchmark.h>
#include <systemc>

#include "config/sensor_config.hpp"
#include "scene/photocurrents.hpp"
#include "scene/scene.hpp"
#include "top/imager_simulation.hpp"

namespace aesim {
namespace {

void run(benchmark::State& state, const SensorConfig& config, const Scene& scene) {
  const Photocurrents light(scene, config.pixel);
  std::uint64_t events = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(config, light);
    events += r.log.totals().fired;
    benchmark::DoNotOptimize(r.log.events().data());
  }
  state.counters["events_per_s"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["pixels"] = config.array.rows * config.array.cols;
}

void BM_AlohaLetterA(benchmark::State& state) {
  SensorConfig c = load_sensor("aloha");
  c.sim.duration = 10.0;
  run(state, c, load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/letters/A.pgm"), c));
}

void BM_QcifBrightUniform(benchmark::State& state) {
  SensorConfig c = load_sensor("aloha");
  c.array.rows = 144;
  c.array.cols = 176;
  c.sim.duration = 2.0;
  run(state, c, load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/uniform.pgm"), c));
}

BENCHMARK(BM_AlohaLetterA)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_QcifBrightUniform)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace aesim

int sc_main(int argc, char* argv[]) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
