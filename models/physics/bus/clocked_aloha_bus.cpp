#include "aesim/bus/clocked_aloha_bus.hpp"

namespace aesim {

ClockedAlohaBus::ClockedAlohaBus(const sc_core::sc_module_name& name, ReceiverSignals& wires,
                                 sc_core::sc_time clock_period, bool contention_detect, EventLog& log)
    : sc_module(name), s_(wires), clock_period_(clock_period), detect_(contention_detect), log_(log) {
  SC_METHOD(on_ack);
  sensitive << s_.ack;
  dont_initialize();
  SC_METHOD(apply_deferred);
  sensitive << deferred_event_;
  dont_initialize();
}

void ClockedAlohaBus::drive() {
  if (lines_.req() != s_.req.read()) rules_.req_changed(lines_.req(), s_.ack.read());
  s_.addr.write(lines_.addr());
  s_.req.write(lines_.req());
  s_.contention.write(lines_.contention());
}

void ClockedAlohaBus::request(const AddressEvent& firing) {
  log_.fired(firing);
  if (sc_core::sc_time_stamp().value() % clock_period_.value() == 0) {
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
  if (!lines_.join(firing, firing.bus_address, s_.ack.read())) {
    log_.resolve(firing, Fate::Absorbed);
    return;
  }
  if (!in_transaction_) {
    in_transaction_ = true;
    transaction_start_ = sc_core::sc_time_stamp();
  }
  drive();
}

void ClockedAlohaBus::on_ack() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  rules_.ack_changed(s_.ack.read(), s_.req.read());
  if (!s_.ack.read()) {
    // An Ack that rose with no Req (a broken receiver) ends no transaction.
    if (in_transaction_) {
      busy_time_ += (now - transaction_start_).to_seconds();
      ++transactions_;
      in_transaction_ = false;
    }
    return;
  }
  // The receiver latched at this edge: every driver on the wires then was seen. It may have
  // stored the event, discarded a flagged collision, or dropped it for a full FIFO.
  const bool dropped = s_.overflows.read() != overflows_seen_;
  overflows_seen_ = s_.overflows.read();
  const Fate lost = dropped ? Fate::Dropped : detect_ ? Fate::Collided : Fate::Ghost;
  lines_.release(seen_);
  for (const AddressEvent& firing : seen_) {
    if (seen_.size() == 1 && !dropped) log_.resolve(firing, Fate::Delivered, now.to_seconds());
    else log_.resolve(firing, lost);
  }
  drive();
}

double ClockedAlohaBus::measured_tau() const {
  return transactions_ == 0 ? 0.0 : busy_time_ / static_cast<double>(transactions_);
}

}  // namespace aesim
