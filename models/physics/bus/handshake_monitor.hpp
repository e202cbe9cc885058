#pragma once
#include <cstdint>
#include <string>
#include <systemc>

#include "waveform/vcd_recorder.hpp"

namespace aesim {

// Watches one tile's bus wires. Checks the 4-phase handshake: Req rises only while Ack is low,
// Ack rises only while Req is high, Req falls only while Ack is high, Ack falls only while Req
// is low (so one transaction at a time). Optionally records every change for a VCD file.
class HandshakeMonitor : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> req, ack, contention;
  sc_core::sc_in<std::uint32_t> addr;

  HandshakeMonitor(const sc_core::sc_module_name& name, const std::string& scope, int addr_bits,
                   VcdRecorder* vcd);
  SC_HAS_PROCESS(HandshakeMonitor);

  std::uint64_t violations() const { return violations_; }

 private:
  void on_req();
  void on_ack();
  void on_data();
  void record(int id, std::uint64_t value);

  VcdRecorder* vcd_;
  int id_req_ = 0, id_ack_ = 0, id_contention_ = 0, id_addr_ = 0;
  std::uint64_t violations_ = 0;
};

}  // namespace aesim
