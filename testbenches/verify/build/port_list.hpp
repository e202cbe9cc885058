#pragma once
#include <string>
#include <vector>

namespace aesim {

// A port of a Verilated top module, as Verilator declared it in the model's header.
struct RtlPort {
  std::string name;    // in the Verilog
  std::string member;  // in Verilator's C++, where some names are spelt otherwise (verilog_name_of)
  bool input = true;
  int msb = 0, lsb = 0;  // as declared; [msb:lsb] with msb >= lsb for a descending range
  int width = 1;         // bits
  // Verilator's storage: 1, 2, 4 or 8 bytes, or 0 for a port of over 64 bits (32-bit words).
  int bytes = 1;
  bool wide() const { return bytes == 0; }
};

// The Verilog name of a Verilated member: Verilator spells a character C++ names cannot hold as
// __0 and its two hex digits (a '$' as __024, and the second of two underscores as __05F), and a
// C++ keyword with __SYM__ before it (a port called `switch`).
std::string verilog_name_of(const std::string& member);

// The ports declared in a Verilated model header (VL_IN8(&name,msb,lsb); and so on).
std::vector<RtlPort> ports_in_verilated_header(const std::string& header_text);

// The list as one line per port ("in 9 0 2 addr": direction, msb, lsb, bytes, name), the form the
// build cache keeps.
std::string port_list_text(const std::vector<RtlPort>& ports);
std::vector<RtlPort> parse_port_list_text(const std::string& text);

const RtlPort* find_port(const std::vector<RtlPort>& ports, const std::string& name);

}  // namespace aesim
