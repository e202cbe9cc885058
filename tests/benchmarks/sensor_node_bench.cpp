// The source paper's sensor node as a virtual platform against the event rung alone, on the same
// 2 s ALOHA scene (the aloha preset on a hand sign at its default light): simulated seconds per wall
// second, side by side in one run. Both build the scene's configuration and photocurrents and run
// the event rung; the node adds the SystemC platform (the event FIFO, the processor running the
// recogniser as timed firmware) and simulates it. scripts/bench prints the ratios.
#include <benchmark/benchmark.h>
#include <systemc>
#include <tlm>

#include <string>
#include <vector>

#include "aesim/classify/template_classifier.hpp"
#include "aesim/embed/event_fifo_target.hpp"
#include "aesim/embed/event_source.hpp"
#include "aesim/kernel/systemc_kernel.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/sensor_node/node_processor.hpp"

namespace aesim {
namespace {

constexpr double kDuration = 2.0;

ImagerSpec scene_spec() {
  ImagerSpec spec;
  spec.scene = std::string(AESIM_SOURCE_DIR) + "/scenes/hand_signs/victory.pgm";
  spec.settings = {{"sim.duration", "2s"}};
  return spec;
}

void report(benchmark::State& state) {
  state.counters["sim_s_per_s"] =
      benchmark::Counter(kDuration * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The least the node must also do: the event rung on the scene, from its spec.
void BM_SensorNodeScene_event_rung(benchmark::State& state) {
  const ImagerSpec spec = scene_spec();
  for (auto _ : state) {
    const SpecInputs in = spec_inputs(spec, Fidelity::Event, "", "aesim/bench");
    const SimulationResult r = simulate(in.config, in.photocurrents);
    benchmark::DoNotOptimize(r.log.events().data());
  }
  report(state);
}

void BM_SensorNodeScene_node(benchmark::State& state, bool approximately_timed, double clock_hz, std::uint32_t depth) {
  const ImagerSpec spec = scene_spec();
  const std::vector<Template> templates = load_templates(std::string(AESIM_SOURCE_DIR) + "/scenes/templates/hand_signs");
  tlm::tlm_global_quantum::instance().set(sc_core::sc_time(1, sc_core::SC_MS));
  NodeProcessorConfig config;
  config.approximately_timed = approximately_timed;
  config.clock_hz = clock_hz;
  std::uint64_t decisions = 0;
  for (auto _ : state) {
    const ScopedKernel kernel;
    EventSource source("source", spec);
    EventFifoTarget fifo("fifo", depth, source.tick());
    fifo.deliver(source.events());
    sc_core::sc_signal<bool> irq("irq");
    fifo.irq(irq);
    NodeProcessor cpu("cpu", templates, config, &fifo);
    cpu.socket.bind(fifo.socket);
    cpu.irq(irq);
    sc_core::sc_start(sc_core::sc_time(kDuration, sc_core::SC_SEC));
    decisions += cpu.decisions().size();
  }
  report(state);
  state.counters["decisions"] = static_cast<double>(decisions) / static_cast<double>(state.iterations());
}

void repeated(benchmark::internal::Benchmark* b) {
  // Wall time: the event rung's tile threads work beside the benchmark's own thread.
  b->Unit(benchmark::kMillisecond)->MinTime(0.5)->UseRealTime()->Repetitions(6)->DisplayAggregatesOnly(true);
}
BENCHMARK(BM_SensorNodeScene_event_rung)->Apply(repeated);
BENCHMARK_CAPTURE(BM_SensorNodeScene_node, loose, false, 57.6e6, 64)->Apply(repeated);
BENCHMARK_CAPTURE(BM_SensorNodeScene_node, loose_slow_lossy, false, 1.8e6, 16)->Apply(repeated);
BENCHMARK_CAPTURE(BM_SensorNodeScene_node, approximate, true, 57.6e6, 64)->Apply(repeated);

}  // namespace
}  // namespace aesim
