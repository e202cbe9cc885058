#pragma once
#include "array/address_map.hpp"
#include "config/sensor_config.hpp"
#include "io/summary.hpp"
#include "receiver/event_log.hpp"
#include "scene/photocurrents.hpp"

namespace aesim {

struct SimulationResult {
  EventLog log;
  RunFacts facts;
};

// The fidelity a run uses: sim.fidelity, with auto resolved to the cheapest rung that
// produces what was asked. Throws InputError for a fidelity this build does not model.
Fidelity resolve_fidelity(const SensorConfig& config);

// Elaborates the imager in a fresh SystemC kernel, simulates sim.duration and returns what the
// receivers got, time-ordered. Each call is independent, so one process may run many.
SimulationResult simulate(const SensorConfig& config, const Photocurrents& light);

}  // namespace aesim
