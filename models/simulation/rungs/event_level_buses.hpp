#pragma once
#include <memory>
#include <vector>

#include "aesim/bus/event_bus.hpp"
#include "aesim/bus/event_level_bus.hpp"
#include "aesim/rungs/rung.hpp"

namespace aesim {

// One event-level bus per tile, as bus.access names it: the buses of every rung without wires.
class EventLevelBuses {
 public:
  explicit EventLevelBuses(const RungRun& run) {
    for (int t = 0; t < run.map.tiles(); ++t) {
      buses_.push_back(make_event_level_bus(run.config.bus, run.config.sim.duration, run.map, run.log));
    }
  }
  EventBus& operator[](std::size_t tile) { return *buses_[tile]; }
  std::vector<EventBus*> pointers() const {
    std::vector<EventBus*> out;
    for (const auto& bus : buses_) out.push_back(bus.get());
    return out;
  }
  // Settles what every bus still holds; an event-level bus's transaction time is bus.t_event.
  void finish(const BusParams& params, RunFacts& facts) {
    for (auto& bus : buses_) bus->finish();
    facts.tau_s = params.t_event;
  }

 private:
  std::vector<std::unique_ptr<EventBus>> buses_;
};

}  // namespace aesim
