#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "config/sensor_config.hpp"
#include "receiver/event_log.hpp"

namespace aesim {

struct RunFacts {
  Fidelity fidelity = Fidelity::Event;  // the fidelity that ran (never Auto)
  double tau_s = 0;                     // bus transaction time the loads are computed with
  double sim_time_s = 0;
  double wall_time_s = 0;
};

// Summary JSON of SPEC section 5. offered_load G = fired rate per bus * tau and throughput
// S = successfully delivered (non-ghost) rate per bus * tau, both averaged over the buses.
nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts);

}  // namespace aesim
