#include "io/summary.hpp"

namespace aesim {

nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts) {
  const TileCounters total = log.totals();
  const double buses = static_cast<double>(log.tiles().size());
  const double per_bus_rate = 1.0 / (buses * facts.sim_time_s);
  nlohmann::json tiles = nlohmann::json::array();
  for (const TileCounters& t : log.tiles()) {
    tiles.push_back({{"fired", t.fired}, {"delivered", t.delivered}, {"collided", t.collided},
                     {"ghost", t.ghost}, {"dropped", t.dropped}, {"pending", t.pending}});
  }
  const LatencyStats latency = log.latency();
  return {
      {"events_fired", total.fired},
      {"events_delivered", total.delivered},
      {"events_collided", total.collided},
      {"events_ghost", total.ghost},
      {"events_dropped", total.dropped},
      {"events_pending", total.pending},
      {"offered_load", static_cast<double>(total.fired) * per_bus_rate * facts.tau_s},
      {"throughput", static_cast<double>(total.delivered - total.ghost) * per_bus_rate * facts.tau_s},
      {"collision_fraction", total.fired ? static_cast<double>(total.collided) / total.fired : 0.0},
      {"latency_mean_s", latency.mean},
      {"latency_p99_s", latency.p99},
      {"latency_max_s", latency.max},
      {"tau_s", facts.tau_s},
      {"sim_time_s", facts.sim_time_s},
      {"wall_time_s", facts.wall_time_s},
      {"fidelity", to_string(facts.fidelity)},
      {"protocol_violations", facts.protocol_violations},
      {"receiver_clock_edges", facts.receiver_clock_edges},
      {"receiver_tick_s", facts.tick_s},
      {"scoreboard_beats", facts.scoreboard_beats},
      {"scoreboard_mismatches", facts.scoreboard_mismatches},
      {"fixed_step_multi_fire_steps", facts.multi_fire_steps},
      {"queue_empty_lit_frames", facts.empty_queue_frames},
      {"tiles", tiles},
      {"sensor", config.to_json()},
  };
}

}  // namespace aesim
