#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "config/sensor_config.hpp"
#include "receiver/event_log.hpp"
#include "scene/image.hpp"

namespace aesim {

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

// Summary JSON of SPEC section 5. offered_load G = fired rate per bus * tau and throughput
// S = successfully delivered (non-ghost) rate per bus * tau, both averaged over the buses.
// With the log's per-pixel counts it adds the sizing metrics (pixel rates, dynamic range covered,
// power); with the scene the array saw (`scene`, values of full scale), the PSNR of the histogram
// reconstruction from the events delivered within analysis.window.
nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts,
                            const Image* scene = nullptr);

}  // namespace aesim
