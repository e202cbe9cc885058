#include "bus/clocked_aloha_bus.hpp"

#include <cmath>

#include <fmt/format.h>

namespace aesim {
namespace {

sc_core::sc_time clock_period(const SensorConfig& config) {
  // A whole number of picoseconds, so edges fall exactly on SystemC's time grid.
  return sc_core::sc_time(static_cast<double>(std::max<long long>(1, std::llround(1e12 / config.receiver.clock))),
                          sc_core::SC_PS);
}

}  // namespace

ClockedAlohaBus::ClockedAlohaBus(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
                                 const SensorConfig& config, EventLog& log, VcdRecorder* vcd,
                                 const CycleOptions& options)
    : TileBus(name),
      clock_("clock", s_, clock_period(config), receiver_prescale(config), kReceiverTsWidth,
             options.free_running_clock ? sc_core::sc_time(config.sim.duration, sc_core::SC_SEC)
                                        : sc_core::SC_ZERO_TIME),
      receiver_(options.receiver("receiver", s_, receiver_model_config(config, options))),
      sink_("sink", s_, tile, map, receiver_tick(config), kReceiverTsWidth, log),
      monitor_("monitor", fmt::format("tile{}", tile), map.bus_bits(), vcd),
      stream_monitor_("stream_monitor", s_),
      log_(log),
      detect_(config.bus.contention_detect) {
  if (options.sink_ready) sink_.set_ready_pattern(options.sink_ready);
  const ReceiverCycleModel::Config rc = receiver_model_config(config, options);
  s_.prescale.write(rc.prescale);
  s_.fifo_limit.write(rc.fifo_limit);
  s_.discard_collisions.write(rc.discard_collisions);
  s_.ts_external.write(rc.ts_external);
  monitor_.req(s_.req);
  monitor_.ack(s_.ack);
  monitor_.contention(s_.contention);
  monitor_.addr(s_.addr);
  SC_METHOD(on_ack);
  sensitive << s_.ack;
  dont_initialize();
  SC_METHOD(apply_deferred);
  sensitive << deferred_event_;
  dont_initialize();
}

void ClockedAlohaBus::drive() {
  std::uint32_t address = 0;
  for (const Driver& d : drivers_) address |= d.firing.bus_address;
  s_.addr.write(address);
  s_.req.write(!drivers_.empty());
  s_.contention.write(drivers_.size() >= 2);
}

void ClockedAlohaBus::request(const AddressEvent& firing) {
  log_.fired(firing);
  if (sc_core::sc_time_stamp().value() % clock_.period().value() == 0) {
    deferred_.push_back(firing);
    deferred_event_.notify(sc_core::sc_time(1, sc_core::SC_PS));
    return;
  }
  join(firing);
}

void ClockedAlohaBus::apply_deferred() {
  for (const AddressEvent& f : deferred_) join(f);
  deferred_.clear();
}

void ClockedAlohaBus::join(const AddressEvent& firing) {
  if (s_.ack.read()) {
    log_.resolve(firing, Fate::Collided);  // absorbed by a transaction already acknowledged
    return;
  }
  if (!in_transaction_) {
    in_transaction_ = true;
    transaction_start_ = sc_core::sc_time_stamp();
  }
  drivers_.push_back({firing, sc_core::sc_time_stamp()});
  drive();
}

void ClockedAlohaBus::on_ack() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  if (!s_.ack.read()) {
    busy_time_ += (now - transaction_start_).to_seconds();
    ++transactions_;
    in_transaction_ = false;
    return;
  }
  // The receiver latched at this edge: every driver on the wires then was seen. It may have
  // stored the event, discarded a flagged collision, or dropped it for a full FIFO.
  const bool dropped = s_.overflows.read() != overflows_seen_;
  overflows_seen_ = s_.overflows.read();
  const Fate lost = dropped ? Fate::Dropped : detect_ ? Fate::Collided : Fate::Ghost;
  for (const Driver& d : drivers_) {
    if (drivers_.size() == 1 && !dropped) log_.resolve(d.firing, Fate::Delivered, now.to_seconds());
    else log_.resolve(d.firing, lost);
  }
  drivers_.clear();
  drive();
}

double ClockedAlohaBus::measured_tau() const {
  return transactions_ == 0 ? 0.0 : busy_time_ / static_cast<double>(transactions_);
}

}  // namespace aesim
