#include "aesim/bus/event_level_bus.hpp"

#include <stdexcept>

#include "aesim/bus/aloha_bus.hpp"
#include "aesim/bus/ideal_bus.hpp"

namespace aesim {

std::unique_ptr<EventBus> make_event_level_bus(const BusParams& bus, double t_end, const AddressMap& map,
                                               EventLog& log) {
  switch (bus.access) {
    case BusAccess::Ideal: return std::make_unique<IdealBus>(log);
    case BusAccess::Aloha: return std::make_unique<AlohaBus>(log, map, bus.t_event, bus.contention_detect);
    case BusAccess::Arbitrated: return std::make_unique<ArbitratedBus>(log, bus.t_event, t_end);
  }
  throw std::logic_error("unknown bus access");
}

}  // namespace aesim
