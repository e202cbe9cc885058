#pragma once
#include "bus/tile_bus.hpp"
#include "events/event_log.hpp"

namespace aesim {

// bus.access=ideal: infinite bandwidth, no loss, no delay. Isolates pixel physics.
class IdealBus : public TileBus {
 public:
  IdealBus(const sc_core::sc_module_name& name, EventLog& log) : TileBus(name), log_(log) {}
  void request(const AddressEvent& firing) override {
    log_.fired(firing);
    log_.resolve(firing, Fate::Delivered, firing.t);
    log_.output(firing);
  }

 private:
  EventLog& log_;
};

}  // namespace aesim
