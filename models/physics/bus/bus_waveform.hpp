#pragma once
#include <cstdint>
#include <string>
#include <systemc>

#include "aesim/waveform/vcd_recorder.hpp"

namespace aesim {

// Records every change of one tile's bus wires (Req, Ack, contention, address) for a VCD file.
// Only a run that asks for a VCD has one: its processes wake on every change of the wires.
class BusWaveform : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> req, ack, contention;
  sc_core::sc_in<std::uint32_t> addr;

  BusWaveform(const sc_core::sc_module_name& name, const std::string& scope, int addr_bits, VcdRecorder& vcd);
  SC_HAS_PROCESS(BusWaveform);

 private:
  void on_req();
  void on_ack();
  void on_data();
  void record(int id, std::uint64_t value);

  VcdRecorder& vcd_;
  int id_req_ = 0, id_ack_ = 0, id_contention_ = 0, id_addr_ = 0;
};

}  // namespace aesim
