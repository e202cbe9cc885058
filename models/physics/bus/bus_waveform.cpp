#include "aesim/bus/bus_waveform.hpp"

namespace aesim {

BusWaveform::BusWaveform(const sc_core::sc_module_name& name, const std::string& scope, int addr_bits,
                         VcdRecorder& vcd)
    : sc_module(name), vcd_(vcd) {
  id_req_ = vcd_.add_signal(scope, "req", 1);
  id_ack_ = vcd_.add_signal(scope, "ack", 1);
  id_contention_ = vcd_.add_signal(scope, "contention", 1);
  id_addr_ = vcd_.add_signal(scope, "addr", addr_bits);
  // One process a handshake wire, as the wires change in separate delta cycles: the file lists
  // a time's changes in the order they happened.
  SC_METHOD(on_req);
  sensitive << req;
  dont_initialize();
  SC_METHOD(on_ack);
  sensitive << ack;
  dont_initialize();
  SC_METHOD(on_data);
  sensitive << contention << addr;
  dont_initialize();
}

void BusWaveform::record(int id, std::uint64_t value) { vcd_.change(sc_core::sc_time_stamp().value(), id, value); }

void BusWaveform::on_data() {
  if (contention.event()) record(id_contention_, contention.read());
  if (addr.event()) record(id_addr_, addr.read());
}

void BusWaveform::on_req() { record(id_req_, req.read()); }

void BusWaveform::on_ack() { record(id_ack_, ack.read()); }

}  // namespace aesim
