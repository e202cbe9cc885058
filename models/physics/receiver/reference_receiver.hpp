#pragma once
#include <systemc>

#include "receiver/receiver_cycle_model.hpp"
#include "receiver/receiver_signals.hpp"

namespace aesim {

// The reference receiver as a SystemC module: ReceiverCycleModel clocked by the tile's clock,
// with the same ports as the RTL. Reset (rst_n low) is asynchronous, as in the RTL.
class ReferenceReceiver : public sc_core::sc_module {
 public:
  ReferenceReceiver(const sc_core::sc_module_name& name, ReceiverSignals& s,
                    const ReceiverCycleModel::Config& config);
  SC_HAS_PROCESS(ReferenceReceiver);

 private:
  void on_clock_or_reset();
  void drive();

  ReceiverSignals& s_;
  ReceiverCycleModel model_;
};

// Reads the inputs a receiver saw at this edge, for models stepped beside it.
ReceiverCycleModel::Inputs sample_inputs(const ReceiverSignals& s);

}  // namespace aesim
