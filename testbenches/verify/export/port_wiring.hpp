#pragma once
#include <map>
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"

namespace aesim {

// The receiver's ports as Verilog around an instance of it (the exported testbench, the formal
// checker): every port used, once, as a wire p_PORT of the port's own width; an output read by
// roles (whole or sliced), an input assembled by continuous assignment from the expressions that
// drive its bits (bits no role drives are 0).
class PortWiring {
 public:
  PortWiring(const ReceiverDescription& d, const std::vector<RtlPort>& ports) : d_(d), ports_(ports) {}
  // An output role's bits, e.g. "p_pkt_data[17:8]" (or "{p_evt_y, p_evt_x}" for a joined role).
  std::string read(const std::string& role);
  // An input role's bits (or a whole input port) driven by `expr`.
  void drive(const std::string& role, const std::string& expr);
  void drive(const PortRef& ref, const std::string& expr);
  // A one-bit input raised where the one-bit `expr` is 1, at the level it is active at: a role's
  // (ReceiverDescription::active_high), or the reset's.
  void drive_raised(const std::string& role, const std::string& expr);
  void drive_raised(const PortRef& ref, bool active_high, const std::string& expr);
  // A one-bit output role, 1 where it is raised (whatever level it is active at).
  std::string read_raised(const std::string& role);
  // The wires, one per port, and the instance's port connections.
  std::string declarations() const;
  std::string connections() const;
  // `wire NAME` for the beats: valid as it is, or, for a valid held for each word or toggled for
  // each (ReceiverDescription::valid_beat), high at the edge it rises or changes only (a register
  // of it clocked by `clk`).
  std::string valid_beat(const std::string& name);

 private:
  struct Piece {
    int msb, lsb;
    std::string expr;
  };
  std::string read(const PortRef& ref);

  const ReceiverDescription& d_;
  const std::vector<RtlPort>& ports_;
  std::map<std::string, std::vector<Piece>> used_;
  std::string role_wires_;  // wires of joined input roles, which their parts read
};

}  // namespace aesim
