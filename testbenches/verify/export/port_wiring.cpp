#include "export/port_wiring.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace aesim {
namespace {

std::string range(int msb, int lsb) { return msb == 0 && lsb == 0 ? "" : fmt::format("[{}:{}] ", msb, lsb); }

}  // namespace

std::string PortWiring::read(const std::string& role) { return read(d_.ref(role)); }

std::string PortWiring::read(const PortRef& ref) {
  if (ref.joined()) {
    std::string parts;
    for (const PortRef& part : ref.parts) parts += (parts.empty() ? "" : ", ") + read(part);
    return "{" + parts + "}";
  }
  used_[ref.port];
  if (!ref.sliced()) return "p_" + ref.port;
  return ref.msb == ref.lsb ? fmt::format("p_{}[{}]", ref.port, ref.msb) : fmt::format("p_{}[{}:{}]", ref.port, ref.msb, ref.lsb);
}

void PortWiring::drive(const std::string& role, const std::string& expr) {
  const PortRef& ref = d_.ref(role);
  if (!ref.joined()) return drive(ref, expr);
  // Through a wire of the role's own: each part takes its bits of it.
  const std::string wire = "r_" + role;
  int width = 0;
  std::vector<int> widths;
  for (const PortRef& part : ref.parts) {
    const RtlPort& p = *find_port(ports_, part.port);
    widths.push_back(part.sliced() ? part.msb - part.lsb + 1 : p.width);
    width += widths.back();
  }
  role_wires_ += fmt::format("  wire {}{} = {};\n", range(width - 1, 0), wire, expr);
  int top = width - 1;
  for (std::size_t i = 0; i < ref.parts.size(); ++i) {
    const int lsb = top - widths[i] + 1;
    drive(ref.parts[i], widths[i] == 1 ? fmt::format("{}[{}]", wire, top) : fmt::format("{}[{}:{}]", wire, top, lsb));
    top = lsb - 1;
  }
}

void PortWiring::drive(const PortRef& ref, const std::string& expr) {
  const RtlPort& p = *find_port(ports_, ref.port);
  const int lo = std::min(p.msb, p.lsb);
  used_[ref.port].push_back({ref.sliced() ? ref.msb : lo + p.width - 1, ref.sliced() ? ref.lsb : lo, expr});
}

std::string PortWiring::declarations() const {
  std::string out = role_wires_;
  for (const auto& [name, pieces] : used_) {
    const RtlPort& p = *find_port(ports_, name);
    const int lo = std::min(p.msb, p.lsb), hi = lo + p.width - 1;
    if (!p.input) {
      out += fmt::format("  wire {}p_{};\n", range(hi, lo), name);
      continue;
    }
    // Highest bits first; bits no role drives are 0.
    std::vector<Piece> sorted = pieces;
    std::sort(sorted.begin(), sorted.end(), [](const Piece& a, const Piece& b) { return a.msb > b.msb; });
    std::string concat;
    int next = hi;
    for (const Piece& piece : sorted) {
      if (piece.msb < next) concat += fmt::format("{}{}'d0", concat.empty() ? "" : ", ", next - piece.msb);
      concat += fmt::format("{}{}", concat.empty() ? "" : ", ", piece.expr);
      next = piece.lsb - 1;
    }
    if (next >= lo) concat += fmt::format("{}{}'d0", concat.empty() ? "" : ", ", next - lo + 1);
    out += fmt::format("  wire {}p_{} = {{{}}};\n", range(hi, lo), name, concat);
  }
  return out;
}

std::string PortWiring::connections() const {
  std::string out;
  for (const auto& [name, pieces] : used_) out += fmt::format("{}      .{}(p_{})", out.empty() ? "" : ",\n", name, name);
  return out;
}

void PortWiring::drive_raised(const std::string& role, const std::string& expr) {
  drive_raised(d_.ref(role), d_.active_high(role), expr);
}

void PortWiring::drive_raised(const PortRef& ref, bool active_high, const std::string& expr) {
  drive(ref, active_high ? expr : "!" + expr);
}

std::string PortWiring::read_raised(const std::string& role) {
  const std::string bit = read(role);
  return d_.active_high(role) ? bit : "!" + bit;
}

std::string PortWiring::valid_beat(const std::string& name) {
  const std::string valid = read_raised("valid");
  if (d_.valid_beat == ReceiverDescription::ValidBeat::High) return fmt::format("  wire {} = {};\n", name, valid);
  return fmt::format("  wire valid_level = {};\n  reg valid_was = 1'b0;\n  always @(posedge clk) valid_was <= valid_level;\n"
                     "  wire {} = {};\n",
                     valid, name,
                     d_.valid_beat == ReceiverDescription::ValidBeat::Rise ? "valid_level && !valid_was" : "valid_level != valid_was");
}

}  // namespace aesim
