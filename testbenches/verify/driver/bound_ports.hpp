#pragma once
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "driver/dut_library.hpp"

namespace aesim {

// The description's roles checked against the ports the RTL has: every named port exists, goes
// the right way, and is wide enough (1 bit for the handshake and clock; the bus's address bits;
// the declared timestamp bits; [inputs] values that fit). InputError naming the port otherwise.
void check_ports(const ReceiverDescription& d, const std::vector<RtlPort>& ports, int bus_bits);

// A live model's ports by role.
struct BoundPorts {
  PortAccess clk, reset, req, ack, addr, contention, valid, ready, out_addr, timestamp, flags, overflow;
  bool reset_active_high = false;
  void set_reset(bool active) const { reset.write(active == reset_active_high ? 1 : 0); }
};

// Binds the roles and sets the [inputs] constants.
BoundPorts bind_ports(DutInstance& dut, const ReceiverDescription& d, const std::vector<RtlPort>& ports);

}  // namespace aesim
