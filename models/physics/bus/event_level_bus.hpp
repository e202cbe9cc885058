#pragma once
#include <memory>

#include "aesim/array/address_map.hpp"
#include "aesim/bus/event_bus.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_log.hpp"

namespace aesim {

// The bus that bus.access names, as an event-level model (no wires, no clock): ideal, pure ALOHA
// or arbitrated. `t_end` is the end of the run, past which an arbitrated bus leaves events pending.
std::unique_ptr<EventBus> make_event_level_bus(const BusParams& bus, double t_end, const AddressMap& map,
                                               EventLog& log);

}  // namespace aesim
