#include "bus/clocked_aloha_bus.hpp"

#include <fmt/format.h>

namespace aesim {

ClockedAlohaBus::ClockedAlohaBus(const sc_core::sc_module_name& name, std::uint32_t tile,
                                 const AddressMap& map, const SensorConfig& config, EventLog& log,
                                 VcdRecorder* vcd)
    : TileBus(name),
      req_("req"),
      contention_("contention"),
      addr_("addr"),
      ack_("ack"),
      receiver_("receiver", tile, map, config.receiver.clock, config.bus.contention_detect, log),
      monitor_("monitor", fmt::format("tile{}", tile), map.bus_bits(), vcd),
      log_(log),
      detect_(config.bus.contention_detect) {
  receiver_.req(req_);
  receiver_.addr(addr_);
  receiver_.contention(contention_);
  receiver_.ack(ack_);
  monitor_.req(req_);
  monitor_.ack(ack_);
  monitor_.contention(contention_);
  monitor_.addr(addr_);
  SC_METHOD(on_ack);
  sensitive << ack_;
  dont_initialize();
}

void ClockedAlohaBus::drive() {
  std::uint32_t address = 0;
  for (const Driver& d : drivers_) address |= d.firing.bus_address;
  addr_.write(address);
  req_.write(!drivers_.empty());
  contention_.write(drivers_.size() >= 2);
}

void ClockedAlohaBus::request(const AddressEvent& firing) {
  log_.fired(firing);
  if (ack_.read()) {
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
  if (!ack_.read()) {
    busy_time_ += (now - transaction_start_).to_seconds();
    ++transactions_;
    in_transaction_ = false;
    return;
  }
  // The receiver latched at this very edge, reading the wires as they were before it: drivers
  // that started at this instant were not on them yet, and now meet a raised Ack.
  std::size_t latched = 0;
  for (const Driver& d : drivers_) latched += d.since < now ? 1 : 0;
  const Fate lost = detect_ ? Fate::Collided : Fate::Ghost;
  for (const Driver& d : drivers_) {
    if (!(d.since < now)) log_.resolve(d.firing, Fate::Collided);
    else if (latched == 1) log_.resolve(d.firing, Fate::Delivered, now.to_seconds());
    else log_.resolve(d.firing, lost);
  }
  drivers_.clear();
  drive();
}

double ClockedAlohaBus::measured_tau() const {
  return transactions_ == 0 ? 0.0 : busy_time_ / static_cast<double>(transactions_);
}

}  // namespace aesim
