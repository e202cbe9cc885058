#include "receiver/reference_receiver.hpp"

namespace aesim {

ReceiverCycleModel::Inputs sample_inputs(const ReceiverSignals& s) {
  ReceiverCycleModel::Inputs in;
  in.req = s.req.read();
  in.addr = s.addr.read();
  in.contention = s.contention.read();
  in.ready = s.evt_ready.read();
  in.ts = s.ts.read();
  return in;
}

ReferenceReceiver::ReferenceReceiver(const sc_core::sc_module_name& name, ReceiverSignals& s,
                                     const ReceiverCycleModel::Config& config)
    : sc_module(name), s_(s), model_(config) {
  // One process, like the RTL's always @(posedge clk_i or negedge rst_ni): reset is asynchronous.
  SC_METHOD(on_clock_or_reset);
  sensitive << s_.clk.posedge_event() << s_.rst_n;
}

void ReferenceReceiver::on_clock_or_reset() {
  if (!s_.rst_n.read()) {
    model_.reset();
  } else if (s_.clk.posedge()) {
    model_.clock(sample_inputs(s_));
  } else {
    return;
  }
  drive();
}

void ReferenceReceiver::drive() {
  const ReceiverCycleModel::Outputs o = model_.outputs();
  s_.ack.write(o.ack);
  s_.evt_valid.write(o.valid);
  s_.evt_ts.write(static_cast<std::uint32_t>(o.beat.ts));
  s_.evt_addr.write(o.beat.addr);
  s_.evt_flags.write(o.beat.flags);
  s_.events.write(static_cast<std::uint32_t>(o.events));
  s_.collisions.write(static_cast<std::uint32_t>(o.collisions));
  s_.overflows.write(static_cast<std::uint32_t>(o.overflows));
  s_.fifo_count.write(o.fifo_count);
  s_.idle.write(o.idle);
}

}  // namespace aesim
