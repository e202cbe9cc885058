#pragma once
#include <systemc>

#include "aesim/bus/event_bus.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// What a SystemC pixel sees of its tile's bus: it requests the bus with its address when it fires.
class PixelBusIf : public virtual sc_core::sc_interface {
 public:
  // Called at the firing time (sc_time_stamp() equals firing.t to within 1 ps).
  virtual void request(const AddressEvent& firing) = 0;
};

// The channel that binds SystemC pixels' ports to a tile's EventBus.
class PixelBusPort : public sc_core::sc_module, public PixelBusIf {
 public:
  PixelBusPort(const sc_core::sc_module_name& name, EventBus& bus) : sc_module(name), bus_(bus) {}
  void request(const AddressEvent& firing) override { bus_.request(firing); }

 private:
  EventBus& bus_;
};

}  // namespace aesim
