#pragma once
#include <cstdint>
#include <string>

#include "aesim/receiver/receiver_cycle_model.hpp"

namespace aesim {

// A receiver that a tile's clock domain (ReferenceClockDomain) steps itself, one rising edge per
// clock(), in place of the reference model: the Verilated RTL with its co-simulation scoreboard
// (cosim/stepped_rtl_receiver). The same inputs and outputs as ReceiverCycleModel.
class SteppedReceiver {
 public:
  virtual ~SteppedReceiver() = default;
  // Rising edge number `edge` of the receiver clock; `ts` is the free-running tick count a
  // timestamp counter outside would latch there.
  virtual void clock(const ReceiverCycleModel::Inputs& in, std::uint64_t ts) = 0;
  virtual const ReceiverCycleModel::Outputs& outputs() const = 0;
  virtual std::uint64_t scoreboard_mismatches() const = 0;
  virtual std::uint64_t scoreboard_beats() const = 0;
};

}  // namespace aesim
