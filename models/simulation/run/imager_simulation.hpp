#pragma once
#include <memory>

#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/events/run_facts.hpp"
#include "aesim/rungs/rung.hpp"
#include "aesim/rungs/simulation_request.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/waveform/vcd_recorder.hpp"

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
