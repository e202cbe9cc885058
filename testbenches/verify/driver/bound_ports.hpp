#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "driver/dut_library.hpp"

namespace aesim {

// The description's roles checked against the ports the RTL has: every named port exists, goes
// the right way, holds the slice named, and is wide enough (1 bit for the handshake and clock;
// the bus's address bits; the declared timestamp bits; [inputs] values that fit). InputError
// naming the port otherwise.
void check_ports(const ReceiverDescription& d, const std::vector<RtlPort>& ports, int bus_bits);
// The RTL's inputs the description leaves alone (no role, not the reset, not in [inputs]): aesim
// holds them at 0 throughout, which a second clock or an enable left out of the description
// would make look like a receiver that never answers. In the order the RTL declares them.
std::vector<std::string> inputs_held_at_zero(const ReceiverDescription& d, const std::vector<RtlPort>& ports);

// The width of a role's bits (its slice, its whole port, or its parts together); 0 when a port
// it names is not in `ports`.
int role_width(const ReceiverDescription& d, const std::vector<RtlPort>& ports, const std::string& role);

// A role's bits from one port or slice, or from several joined ({evt_y, evt_x}: the first part
// the most significant), read and written as one number of at most 64 bits.
class JoinedAccess {
 public:
  // A part below those added so far, `width` bits.
  void append(PortAccess part, int width) {
    for (Part& p : parts_) p.shift += width;
    parts_.push_back({part, 0});
  }
  std::uint64_t read() const {
    std::uint64_t v = 0;
    for (const Part& p : parts_) v |= p.access.read() << p.shift;
    return v;
  }
  void write(std::uint64_t v) const {
    for (const Part& p : parts_) p.access.write(v >> p.shift);
  }

 private:
  struct Part {
    PortAccess access;
    int shift;
  };
  std::vector<Part> parts_;
};

// A live model's ports by role, with each one-bit role's polarity applied: aesim reasons in "Req
// raised", "valid raised" and so on whatever levels the RTL uses for them. Unbound roles (no
// ready, no timestamp, ...) ignore writes.
struct BoundPorts {
  PortAccess clk, reset, req, ack, contention, valid, ready, flags, overflow, special;
  JoinedAccess addr, out_addr, timestamp, time_in;
  bool reset_active_high = false, req_active_high = true, ack_active_high = true, valid_active_high = true,
       ready_active_high = true, contention_active_high = true, special_active_high = true;
  std::vector<PortAccess> clk_also;  // further clock inputs on the same clock
  PortAccess out_clk;                // the output side's own clock, if it has one
  void set_clk(bool high) const {
    clk.write(high ? 1 : 0);
    for (const PortAccess& c : clk_also) c.write(high ? 1 : 0);
  }
  void set_out_clk(bool high) const { out_clk.write(high ? 1 : 0); }
  void set_reset(bool active) const { reset.write(active == reset_active_high ? 1 : 0); }
  void set_req(bool raised) const { req.write(raised == req_active_high ? 1 : 0); }
  void set_contention(bool raised) const { contention.write(raised == contention_active_high ? 1 : 0); }
  void set_ready(bool raised) const { ready.write(raised == ready_active_high ? 1 : 0); }
  bool ack_raised() const { return (ack.read() != 0) == ack_active_high; }
  bool valid_raised() const { return (valid.read() != 0) == valid_active_high; }
  // A beat that is no event (an in-band time marker, say): raised only where the role is bound.
  bool special_raised() const { return special.bound() && (special.read() != 0) == special_active_high; }
};

// Binds the roles and sets the [inputs] constants.
BoundPorts bind_ports(DutInstance& dut, const ReceiverDescription& d, const std::vector<RtlPort>& ports);

}  // namespace aesim
