#pragma once
#include <cstdint>

#include "aesim/config/sensor_config.hpp"

namespace aesim {

// What a run reports about itself besides its events: the rung that ran and its own counters.
struct RunFacts {
  Fidelity fidelity = Fidelity::Event;  // the fidelity that ran (never Auto)
  double tau_s = 0;                     // bus transaction time: measured at the cycle fidelity
  double sim_time_s = 0;
  double wall_time_s = 0;
  std::uint64_t protocol_violations = 0;  // handshake rule breaks (cycle fidelity)
  std::uint64_t receiver_clock_edges = 0; // clock edges the receivers simulated (cycle fidelity)
  std::uint64_t scoreboard_mismatches = 0;  // RTL outputs that differed from the reference model
  std::uint64_t scoreboard_beats = 0;       // output beats the scoreboard compared
  double tick_s = 0;                        // the receiver's timestamp resolution
  std::uint64_t multi_fire_steps = 0;       // fixed_step: steps coarser than a pixel's integration
  std::uint64_t empty_queue_frames = 0;     // queue: lit frames too short for one iteration
};

}  // namespace aesim
