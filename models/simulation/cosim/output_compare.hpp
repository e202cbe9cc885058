#pragma once
#include <cstdint>

#include "aesim/receiver/receiver_cycle_model.hpp"

namespace aesim {

// The co-simulation scoreboard's comparison, one place for both ways the RTL runs (on a clock wire,
// cosim/rtl_receiver; stepped, cosim/stepped_rtl_receiver): `check(name, rtl, model)` is called for
// every output (Ack, the stream's valid, the beat while both offer one, every counter, FIFO fill,
// idle), which counts and names what differs.
template <typename Check>
void compare_outputs(const ReceiverCycleModel::Outputs& rtl, const ReceiverCycleModel::Outputs& model, Check&& check) {
  check("ack", rtl.ack, model.ack);
  check("evt_valid", rtl.valid, model.valid);
  if (model.valid && rtl.valid) {
    check("evt_ts", rtl.beat.ts, model.beat.ts);
    check("evt_addr", rtl.beat.addr, model.beat.addr);
    check("evt_flags", rtl.beat.flags, model.beat.flags);
  }
  check("events", rtl.events, model.events);
  check("collisions", rtl.collisions, model.collisions);
  check("overflows", rtl.overflows, model.overflows);
  check("fifo_count", rtl.fifo_count, model.fifo_count);
  check("idle", rtl.idle, model.idle);
}

}  // namespace aesim
