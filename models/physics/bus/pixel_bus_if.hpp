#pragma once
#include <systemc>

#include "events/address_event.hpp"

namespace aesim {

// What a pixel sees of its tile's bus: it requests the bus with its address when it fires.
// Every bus model (ideal, ALOHA, arbitrated, clocked) plugs in behind this interface.
class PixelBusIf : public virtual sc_core::sc_interface {
 public:
  // Called at the firing time (sc_time_stamp() equals firing.t to within 1 ps).
  virtual void request(const AddressEvent& firing) = 0;
};

}  // namespace aesim
