#pragma once
#include <systemc>

#include "bus/pixel_bus_if.hpp"

namespace aesim {

// One tile's bus model, whatever its kind. Pixels call request(); after the run the imager calls
// finish() so the bus can settle what it still holds (an undecided collision cluster, a queue).
class TileBus : public sc_core::sc_module, public PixelBusIf {
 public:
  using sc_core::sc_module::sc_module;
  virtual void finish() {}
  // Mean duration of a bus transaction as this bus measured it (0 when it has none to measure).
  virtual double measured_tau() const { return 0; }
};

}  // namespace aesim
