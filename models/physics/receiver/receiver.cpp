#include "aesim/receiver/receiver.hpp"

namespace aesim {

Receiver::Receiver(const sc_core::sc_module_name& name, const ReceiverCycleModel::Config& config)
    : sc_module(name), config_(config), model_(config) {
  // One process, like the RTL's always @(posedge clk_i or negedge rst_ni): reset is asynchronous.
  SC_METHOD(on_clock_or_reset);
  sensitive << clk.pos() << rst_n;
}

void Receiver::bind(ReceiverSignals& s) {
  clk(s.clk);
  rst_n(s.rst_n);
  req(s.req);
  addr(s.addr);
  contention(s.contention);
  ack(s.ack);
  ts(s.ts);
  prescale(s.prescale);
  fifo_limit(s.fifo_limit);
  discard_collisions(s.discard_collisions);
  ts_external(s.ts_external);
  evt_valid(s.evt_valid);
  evt_flags(s.evt_flags);
  evt_ts(s.evt_ts);
  evt_addr(s.evt_addr);
  evt_ready(s.evt_ready);
  events(s.events);
  collisions(s.collisions);
  overflows(s.overflows);
  fifo_count(s.fifo_count);
  idle(s.idle);
}

ReceiverCycleModel::Config Receiver::settings() const {
  ReceiverCycleModel::Config c = config_;
  if (prescale.size() > 0) c.prescale = prescale->read();
  if (fifo_limit.size() > 0) c.fifo_limit = fifo_limit->read();
  if (discard_collisions.size() > 0) c.discard_collisions = discard_collisions->read();
  if (ts_external.size() > 0) c.ts_external = ts_external->read();
  return c;
}

void Receiver::on_clock_or_reset() {
  if (!rst_n.read()) {
    model_.reset();
    configured_ = false;
  } else if (clk.posedge()) {
    // The settings' inputs are constant during a run, as the RTL's configuration inputs are; they
    // are read at the first edge after reset, when a signal written during elaboration holds its value.
    if (!configured_) {
      model_ = ReceiverCycleModel(settings());
      configured_ = true;
    }
    ReceiverCycleModel::Inputs in;
    in.req = req.read();
    in.addr = addr.read();
    in.contention = contention.size() > 0 && contention->read();
    in.ready = evt_ready.size() == 0 || evt_ready->read();
    in.ts = ts.size() > 0 ? ts->read() : 0;
    model_.clock(in);
  } else {
    return;
  }
  drive();
}

void Receiver::drive() {
  const ReceiverCycleModel::Outputs& o = model_.outputs();
  ack.write(o.ack);
  if (evt_valid.size() > 0) evt_valid->write(o.valid);
  if (evt_ts.size() > 0) evt_ts->write(static_cast<std::uint32_t>(o.beat.ts));
  if (evt_addr.size() > 0) evt_addr->write(o.beat.addr);
  if (evt_flags.size() > 0) evt_flags->write(o.beat.flags);
  if (events.size() > 0) events->write(static_cast<std::uint32_t>(o.events));
  if (collisions.size() > 0) collisions->write(static_cast<std::uint32_t>(o.collisions));
  if (overflows.size() > 0) overflows->write(static_cast<std::uint32_t>(o.overflows));
  if (fifo_count.size() > 0) fifo_count->write(o.fifo_count);
  if (idle.size() > 0) idle->write(o.idle);
}

}  // namespace aesim
