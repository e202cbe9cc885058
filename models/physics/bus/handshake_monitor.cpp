#include "bus/handshake_monitor.hpp"

namespace aesim {

HandshakeMonitor::HandshakeMonitor(const sc_core::sc_module_name& name, const std::string& scope,
                                   int addr_bits, VcdRecorder* vcd)
    : sc_module(name), vcd_(vcd) {
  if (vcd_) {
    id_req_ = vcd_->add_signal(scope, "req", 1);
    id_ack_ = vcd_->add_signal(scope, "ack", 1);
    id_contention_ = vcd_->add_signal(scope, "contention", 1);
    id_addr_ = vcd_->add_signal(scope, "addr", addr_bits);
  }
  SC_METHOD(on_req);
  sensitive << req;
  dont_initialize();
  SC_METHOD(on_ack);
  sensitive << ack;
  dont_initialize();
  if (vcd_) {
    SC_METHOD(on_data);  // the data wires carry no protocol rule, only waveforms
    sensitive << contention << addr;
    dont_initialize();
  }
}

void HandshakeMonitor::record(int id, std::uint64_t value) {
  if (vcd_) vcd_->change(sc_core::sc_time_stamp().value(), id, value);
}

void HandshakeMonitor::on_data() {
  if (contention.event()) record(id_contention_, contention.read());
  if (addr.event()) record(id_addr_, addr.read());
}

void HandshakeMonitor::on_req() {
  const bool r = req.read();
  if (r == ack.read()) ++violations_;  // rising needs Ack low; falling needs Ack high
  record(id_req_, r);
}

void HandshakeMonitor::on_ack() {
  const bool a = ack.read();
  if (a != req.read()) ++violations_;  // rising needs Req high; falling needs Req low
  record(id_ack_, a);
}

}  // namespace aesim
