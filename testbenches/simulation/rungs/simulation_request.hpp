#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "receiver/receiver_module.hpp"

namespace aesim {

// What a run must produce beyond events and counters.
struct SimulationRequest {
  bool keep_truth = false;          // a TruthRecord per fired event (--truth)
  bool waveforms = false;           // bus waveforms (--vcd): needs a rung with wires
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

}  // namespace aesim
