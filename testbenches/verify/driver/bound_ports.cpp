#include "driver/bound_ports.hpp"

#include <fmt/format.h>

#include "errors/input_error.hpp"

namespace aesim {
namespace {

[[noreturn]] void port_error(const ReceiverDescription& d, const std::string& key, const std::string& what) {
  throw InputError(fmt::format("receiver description '{}': {}: {}", d.file, key, what));
}

const RtlPort& need(const ReceiverDescription& d, const std::vector<RtlPort>& ports, const std::string& key,
                    const std::string& name, bool input) {
  const RtlPort* p = find_port(ports, name);
  if (!p) port_error(d, key, fmt::format("the RTL (top {}) has no port '{}'", d.top, name));
  if (p->input != input) port_error(d, key, fmt::format("port {} is an {}; aesim expects an {}", name, p->input ? "input" : "output", input ? "input" : "output"));
  if (p->bytes == 0) port_error(d, key, fmt::format("port {} is {} bits; aesim connects ports of up to 64 bits", name, p->width));
  return *p;
}

}  // namespace

void check_ports(const ReceiverDescription& d, const std::vector<RtlPort>& ports, int bus_bits) {
  for (const PortRole& role : port_roles()) {
    if (!d.has(role.name)) continue;
    const std::string key = fmt::format("ports.{}", role.name);
    const RtlPort& p = need(d, ports, key, d.port(role.name), role.input);
    const std::string r = role.name;
    const bool one_bit = r == "clk" || r == "req" || r == "ack" || r == "contention" || r == "valid" || r == "ready";
    if (one_bit && p.width != 1) port_error(d, key, fmt::format("port {} is {} bits; {} is one bit", p.name, p.width, r));
    if ((r == "addr" || r == "out_addr") && p.width < bus_bits) {
      port_error(d, key, fmt::format("port {} is {} bits; the bus carries {}-bit addresses", p.name, p.width, bus_bits));
    }
    if (r == "timestamp" && p.width < d.timestamp_bits) {
      port_error(d, key, fmt::format("port {} is {} bits; behaviour.timestamp_bits is {}", p.name, p.width, d.timestamp_bits));
    }
  }
  const RtlPort& reset = need(d, ports, "reset.port", d.reset_port, true);
  if (reset.width != 1) port_error(d, "reset.port", fmt::format("port {} is {} bits; a reset is one bit", reset.name, reset.width));
  for (const auto& [name, value] : d.inputs) {
    const RtlPort& p = need(d, ports, "inputs." + name, name, true);
    if (p.width < 64 && (value >> p.width) != 0) {
      port_error(d, "inputs." + name, fmt::format("{} does not fit the {} bits of port {}", value, p.width, name));
    }
  }
}

BoundPorts bind_ports(DutInstance& dut, const ReceiverDescription& d, const std::vector<RtlPort>& ports) {
  auto bind = [&](const std::string& name) {
    const RtlPort* p = find_port(ports, name);
    return dut.port(name, p->bytes, p->width);
  };
  auto role = [&](const char* r) { return d.has(r) ? bind(d.port(r)) : PortAccess(); };
  BoundPorts b;
  b.clk = role("clk");
  b.req = role("req");
  b.ack = role("ack");
  b.addr = role("addr");
  b.contention = role("contention");
  b.valid = role("valid");
  b.ready = role("ready");
  b.out_addr = role("out_addr");
  b.timestamp = role("timestamp");
  b.flags = role("flags");
  b.overflow = role("overflow_count");
  b.reset = bind(d.reset_port);
  b.reset_active_high = d.reset_active_high;
  for (const auto& [name, value] : d.inputs) bind(name).write(value);
  return b;
}

}  // namespace aesim
