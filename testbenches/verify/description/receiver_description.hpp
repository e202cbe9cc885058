#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace aesim {

// A team's receiver RTL as its description file (SPEC section 6) says: how to build it, which of
// its ports plays which role, and what it promises. Paths are absolute (relative ones in the file
// are taken from the file's folder).
struct ReceiverDescription {
  enum class Collisions { Discard, Flag, Pass };
  enum class Full { Drop, Hold };

  std::string file;  // the description itself, for messages
  std::string top;
  std::vector<std::string> sources, include_dirs;
  std::map<std::string, std::string> defines;     // NAME -> value ("" for a bare define)
  std::map<std::string, std::string> parameters;  // NAME -> Verilog literal (strings quoted)
  double clock_hz = 0;
  std::string reset_port;
  bool reset_active_high = false;
  std::map<std::string, std::string> ports;        // role -> RTL port name
  std::map<std::string, std::uint64_t> inputs;     // RTL port -> constant value
  Collisions collisions = Collisions::Discard;
  Full full = Full::Drop;
  double timestamp_tick = 0;  // s
  int timestamp_bits = 0;
  int ack_latency_min = 0, ack_latency_max = 0;  // clock edges

  bool has(const std::string& role) const { return ports.count(role) != 0; }
  const std::string& port(const std::string& role) const { return ports.at(role); }
};

// The roles of SPEC section 6, required ones first; `optional` says which may be left out.
struct PortRole {
  const char* name;
  bool input;  // driven by aesim
  bool optional;
};
const std::vector<PortRole>& port_roles();

// Reads and checks a description; every problem is an InputError naming the file and the key.
ReceiverDescription read_receiver_description(const std::string& path);

const char* to_string(ReceiverDescription::Collisions c);
const char* to_string(ReceiverDescription::Full f);

}  // namespace aesim
