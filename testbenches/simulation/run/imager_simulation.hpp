#pragma once
#include <functional>
#include <memory>

#include "array/address_map.hpp"
#include "config/sensor_config.hpp"
#include "events/run_facts.hpp"
#include "waveform/vcd_recorder.hpp"
#include "events/event_log.hpp"
#include "receiver/receiver_module.hpp"
#include "scene/photocurrents.hpp"

namespace aesim {

// What a run must produce beyond events and counters.
struct SimulationRequest {
  bool keep_truth = false;       // a TruthRecord per fired event (--truth)
  bool waveforms = false;        // bus waveforms (--vcd): needs the cycle fidelity
  double vcd_from = 0, vcd_to = 0;  // s, the VCD window
  // With the RTL receiver, also trace tile N's RTL internals (Verilator) to rtl_trace_path(N).
  std::function<std::string(int tile)> rtl_trace_path;
  // Cycle fidelity: back-pressure on every receiver's output, and a free-running receiver clock
  // (see CycleOptions). The receiver itself follows receiver.model.
  std::function<bool(std::uint64_t)> sink_ready;
  bool free_running_clock = false;
  // A receiver to use instead of the one receiver.model names (verification of RTL variants).
  ReceiverFactory receiver;
};

struct SimulationResult {
  EventLog log;
  RunFacts facts;
  std::unique_ptr<VcdRecorder> vcd;
};

// The fidelity a run uses: sim.fidelity, with auto resolved to the cheapest rung that produces
// what was asked (event, or cycle when waveforms are wanted). Throws InputError for a fidelity
// this build does not model or one that cannot produce the request.
Fidelity resolve_fidelity(const SensorConfig& config, const SimulationRequest& request);

// Elaborates the imager in a fresh SystemC kernel (a ScopedKernel), simulates sim.duration and returns what the
// receivers got, time-ordered. Each call is independent, so one process may run many.
SimulationResult simulate(const SensorConfig& config, const Photocurrents& light,
                          const SimulationRequest& request = {});

}  // namespace aesim
