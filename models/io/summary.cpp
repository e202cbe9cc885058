#include "io/summary.hpp"

namespace aesim {

nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts) {
  const TileCounters total = log.totals();
  const double buses = static_cast<double>(log.tiles().size());
  const double per_bus_rate = 1.0 / (buses * facts.sim_time_s);
  nlohmann::json tiles = nlohmann::json::array();
  for (const TileCounters& t : log.tiles()) {
    tiles.push_back({{"fired", t.fired}, {"delivered", t.delivered}, {"collided", t.collided},
                     {"ghost", t.ghost}, {"dropped", t.dropped}});
  }
  return {
      {"events_fired", total.fired},
      {"events_delivered", total.delivered},
      {"events_collided", total.collided},
      {"events_ghost", total.ghost},
      {"events_dropped", total.dropped},
      {"offered_load", static_cast<double>(total.fired) * per_bus_rate * facts.tau_s},
      {"throughput", static_cast<double>(total.delivered - total.ghost) * per_bus_rate * facts.tau_s},
      {"tau_s", facts.tau_s},
      {"sim_time_s", facts.sim_time_s},
      {"wall_time_s", facts.wall_time_s},
      {"fidelity", to_string(facts.fidelity)},
      {"tiles", tiles},
      {"sensor", config.to_json()},
  };
}

}  // namespace aesim
