#include "driver/bound_ports.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

[[noreturn]] void port_error(const ReceiverDescription& d, const std::string& key, const std::string& what) {
  throw InputError(fmt::format("receiver description '{}': {}: {}", d.file, key, what));
}

const RtlPort& need(const ReceiverDescription& d, const std::vector<RtlPort>& ports, const std::string& key,
                    const PortRef& ref, bool input) {
  const RtlPort* p = find_port(ports, ref.port);
  if (!p) port_error(d, key, fmt::format("the RTL (top {}) has no port '{}'", d.top, ref.port));
  if (p->input != input) {
    port_error(d, key, fmt::format("port {} is an {}; aesim expects an {}", ref.port, p->input ? "input" : "output",
                                   input ? "input" : "output"));
  }
  const int lo = std::min(p->msb, p->lsb), hi = std::max(p->msb, p->lsb);
  if (ref.sliced() && (ref.lsb < lo || ref.msb > hi)) {
    port_error(d, key, fmt::format("{} is outside port {} [{}:{}]", ref.text(), ref.port, p->msb, p->lsb));
  }
  if (!ref.sliced() && p->wide()) {
    port_error(d, key, fmt::format("port {} is {} bits; name the bits of this role, e.g. {}[{}:{}]", ref.port, p->width,
                                   ref.port, lo + 15, lo));
  }
  return *p;
}

PortAccess bind(DutInstance& dut, const RtlPort& p, const PortRef& ref) {
  const int lo = std::min(p.msb, p.lsb);
  return ref.sliced() ? dut.port(p.name, p.bytes, ref.lsb - lo, ref.msb - ref.lsb + 1) : dut.port(p.name, p.bytes, 0, p.width);
}

int piece_width(const std::vector<RtlPort>& ports, const PortRef& ref) {
  const RtlPort* p = find_port(ports, ref.port);
  if (!p) return 0;
  return ref.sliced() ? ref.msb - ref.lsb + 1 : p->width;
}

}  // namespace

int role_width(const ReceiverDescription& d, const std::vector<RtlPort>& ports, const std::string& role) {
  int width = 0;
  for (const PortRef& piece : d.ref(role).pieces()) {
    const int w = piece_width(ports, piece);
    if (w == 0) return 0;
    width += w;
  }
  return width;
}

void check_ports(const ReceiverDescription& d, const std::vector<RtlPort>& ports, int bus_bits) {
  for (const PortRole& role : port_roles()) {
    if (!d.has(role.name)) continue;
    const std::string key = fmt::format("ports.{}", role.name);
    for (const PortRef& piece : d.ref(role.name).pieces()) need(d, ports, key, piece, role.input);
    const std::string r = role.name;
    const int width = role_width(d, ports, r);
    const std::string what = d.ref(r).text();
    if (d.ref(r).joined() && width > 64) port_error(d, key, fmt::format("{} is {} bits; aesim joins up to 64", what, width));
    const bool one_bit =
        r == "clk" || r == "req" || r == "ack" || r == "contention" || r == "valid" || r == "ready" || r == "special";
    if (one_bit && width != 1) port_error(d, key, fmt::format("{} is {} bits; {} is one bit", what, width, r));
    if ((r == "addr" || r == "out_addr") && width < bus_bits) {
      port_error(d, key, fmt::format("{} is {} bits; the bus carries {}-bit addresses", what, width, bus_bits));
    }
    if (r == "timestamp" && width < d.timestamp_bits) {
      port_error(d, key, fmt::format("{} is {} bits; behaviour.timestamp_bits is {}", what, width, d.timestamp_bits));
    }
  }
  std::vector<std::string> clocks = d.clock_also;
  if (d.has_out_clock()) clocks.push_back(d.out_clock_port);
  for (const std::string& name : clocks) {
    const RtlPort& clock = need(d, ports, "ports.clk", PortRef{name}, true);
    if (clock.width != 1) port_error(d, "ports.clk", fmt::format("port {} is {} bits; a clock is one bit", name, clock.width));
  }
  if (d.has_reset()) {
    const RtlPort& reset = need(d, ports, "reset.port", PortRef{d.reset_port}, true);
    if (reset.width != 1) port_error(d, "reset.port", fmt::format("port {} is {} bits; a reset is one bit", reset.name, reset.width));
  }
  for (const auto& [name, value] : d.inputs) {
    const RtlPort& p = need(d, ports, "inputs." + name, PortRef{name}, true);
    if (p.width < 64 && (value >> p.width) != 0) {
      port_error(d, "inputs." + name, fmt::format("{} does not fit the {} bits of port {}", value, p.width, name));
    }
  }
}

std::vector<std::string> inputs_held_at_zero(const ReceiverDescription& d, const std::vector<RtlPort>& ports) {
  std::vector<std::string> held;
  for (const RtlPort& p : ports) {
    if (!p.input || p.name == d.reset_port || d.inputs.count(p.name)) continue;
    if (std::find(d.clock_also.begin(), d.clock_also.end(), p.name) != d.clock_also.end() || p.name == d.out_clock_port) continue;
    const bool has_role = std::any_of(d.ports.begin(), d.ports.end(), [&](const auto& role) { return role.second.uses(p.name); });
    if (!has_role) held.push_back(p.name);
  }
  return held;
}

BoundPorts bind_ports(DutInstance& dut, const ReceiverDescription& d, const std::vector<RtlPort>& ports) {
  auto role = [&](const char* r) {
    return d.has(r) ? bind(dut, *find_port(ports, d.port(r)), d.ref(r)) : PortAccess();
  };
  auto joined = [&](const char* r) {
    JoinedAccess access;
    if (!d.has(r)) return access;
    for (const PortRef& piece : d.ref(r).pieces()) access.append(bind(dut, *find_port(ports, piece.port), piece), piece_width(ports, piece));
    return access;
  };
  BoundPorts b;
  b.clk = role("clk");
  for (const std::string& name : d.clock_also) b.clk_also.push_back(bind(dut, *find_port(ports, name), PortRef{name}));
  if (d.has_out_clock()) b.out_clk = bind(dut, *find_port(ports, d.out_clock_port), PortRef{d.out_clock_port});
  b.req = role("req");
  b.ack = role("ack");
  b.addr = joined("addr");
  b.contention = role("contention");
  b.valid = role("valid");
  b.ready = role("ready");
  b.out_addr = joined("out_addr");
  b.timestamp = joined("timestamp");
  b.time_in = joined("time_in");
  b.flags = role("flags");
  b.overflow = role("overflow_count");
  b.special = role("special");
  if (d.has_reset()) b.reset = bind(dut, *find_port(ports, d.reset_port), PortRef{d.reset_port});
  b.reset_active_high = d.reset_active_high;
  b.req_active_high = d.active_high("req");
  b.ack_active_high = d.active_high("ack");
  b.valid_active_high = d.active_high("valid");
  b.ready_active_high = d.active_high("ready");
  b.contention_active_high = d.active_high("contention");
  b.special_active_high = d.active_high("special");
  for (const auto& [name, value] : d.inputs) bind(dut, *find_port(ports, name), PortRef{name}).write(value);
  return b;
}

}  // namespace aesim
