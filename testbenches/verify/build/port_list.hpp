#pragma once
#include <string>
#include <vector>

namespace aesim {

// A port of a Verilated top module, as Verilator declared it in the model's header.
struct RtlPort {
  std::string name;
  bool input = true;
  int width = 1;   // bits
  int bytes = 1;   // storage: 1, 2, 4 or 8; 0 for ports wider than 64 bits (not driven by aesim)
};

// The ports declared in a Verilated model header (VL_IN8(&name,msb,lsb); and so on).
std::vector<RtlPort> ports_in_verilated_header(const std::string& header_text);

// The list as one line per port ("in 10 2 addr"), the form the build cache keeps.
std::string port_list_text(const std::vector<RtlPort>& ports);
std::vector<RtlPort> parse_port_list_text(const std::string& text);

const RtlPort* find_port(const std::vector<RtlPort>& ports, const std::string& name);

}  // namespace aesim
