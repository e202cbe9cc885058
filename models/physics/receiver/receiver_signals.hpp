#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/receiver/receiver_cycle_model.hpp"

namespace aesim {

// The wires around one tile's receiver, with the port names of rtl/aer_receiver.v. Widths up to
// 32 bits travel as uint32_t, as Verilator's SystemC models expect. Whatever receiver a tile
// uses (the reference model or the Verilated RTL) binds to these.
struct ReceiverSignals {
  sc_core::sc_signal<bool> clk{"clk"}, rst_n{"rst_n"};
  // The bus: Req, address and contention are wired-OR lines driven by every pixel that fires.
  sc_core::sc_signal<bool, sc_core::SC_MANY_WRITERS> req{"req"}, contention{"contention"};
  sc_core::sc_signal<std::uint32_t, sc_core::SC_MANY_WRITERS> addr{"addr"};
  sc_core::sc_signal<bool> ack{"ack"};
  // Configuration, set before the run.
  sc_core::sc_signal<std::uint32_t> prescale{"prescale"}, fifo_limit{"fifo_limit"};
  sc_core::sc_signal<bool> discard_collisions{"discard_collisions"}, ts_external{"ts_external"};
  sc_core::sc_signal<std::uint32_t> ts{"ts"};
  // The event stream and status.
  sc_core::sc_signal<bool> evt_valid{"evt_valid"}, evt_ready{"evt_ready"}, evt_flags{"evt_flags"};
  sc_core::sc_signal<std::uint32_t> evt_ts{"evt_ts"}, evt_addr{"evt_addr"};
  sc_core::sc_signal<std::uint32_t> events{"events"}, collisions{"collisions"}, overflows{"overflows"},
      fifo_count{"fifo_count"};
  sc_core::sc_signal<bool> idle{"idle"};
};

// The inputs a receiver sees at this edge, for models stepped beside it.
inline ReceiverCycleModel::Inputs sample_inputs(const ReceiverSignals& s) {
  ReceiverCycleModel::Inputs in;
  in.req = s.req.read();
  in.addr = s.addr.read();
  in.contention = s.contention.read();
  in.ready = s.evt_ready.read();
  in.ts = s.ts.read();
  return in;
}

}  // namespace aesim
