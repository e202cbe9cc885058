#pragma once
#include <memory>

#include "config/sensor_config.hpp"
#include "events/event_log.hpp"
#include "events/run_facts.hpp"
#include "rungs/rung.hpp"
#include "rungs/simulation_request.hpp"
#include "scene/photocurrents.hpp"
#include "waveform/vcd_recorder.hpp"

namespace aesim {

struct SimulationResult {
  EventLog log;
  RunFacts facts;
  std::unique_ptr<VcdRecorder> vcd;
};

// Simulates sim.duration on the rung choose_rung() picks and returns what the receivers got,
// time-ordered. The work is estimated and bounded first (rungs/run_budget). Each call is
// independent (rungs under SystemC get a kernel of their own), so one process may run many.
SimulationResult simulate(const ResolvedConfig& config, const Photocurrents& photocurrents,
                          const SimulationRequest& request = {});

}  // namespace aesim
