#pragma once
#include <systemc>

#include "bus/pixel_bus_if.hpp"
#include "receiver/event_log.hpp"

namespace aesim {

// bus.access=ideal: infinite bandwidth, no loss, no delay. Isolates pixel physics.
class IdealBus : public sc_core::sc_module, public PixelBusIf {
 public:
  IdealBus(const sc_core::sc_module_name& name, EventLog& log) : sc_module(name), log_(log) {}
  void request(const AddressEvent& firing) override {
    log_.fired(firing.tile);
    log_.deliver(firing);
  }

 private:
  EventLog& log_;
};

}  // namespace aesim
