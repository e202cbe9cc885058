#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "aesim/events/event_stream.hpp"
#include "aesim/receiver/receiver_module.hpp"

namespace aesim {

// What a run must produce beyond events and counters.
struct SimulationRequest {
  bool keep_events = true;          // the output events (--out, --csv), not only their counts
  bool keep_truth = false;          // a TruthRecord per fired event (--truth)
  // Where kept records go as the run makes them (the file writers); null: collected in the
  // result's log (events(), truth()).
  EventStream* stream = nullptr;
  // Fired events per window of a streaming run (the event rung): the pace of hand-overs, never
  // the output (tests vary it to show that). 0: chosen from the array (see event_rung.cpp).
  double window_events = 0;
  bool waveforms = false;           // bus waveforms (--vcd): needs a rung with wires
  double vcd_from = 0, vcd_to = 0;  // s, the VCD window
  // With the RTL receiver, also trace tile N's RTL internals (Verilator) to rtl_trace_path(N).
  std::function<std::string(int tile)> rtl_trace_path;
  // How the cycle rung builds its tiles: back-pressure on every receiver's output, a free-running
  // receiver clock, and a receiver to use instead of the one receiver.model names (verification of
  // RTL variants).
  CycleOptions cycle;
};

}  // namespace aesim
