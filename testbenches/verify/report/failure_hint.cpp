#include "report/failure_hint.hpp"

#include <cctype>

#include <fmt/format.h>

namespace aesim {
namespace {

// Whether a port's name says it is active low, as designers name such lines: a suffix _n, _b,
// _l, _bar, _n_i or _ni, or a role name run on into an n ("reqn", "ackn").
bool named_active_low(const std::string& port) {
  std::string l;
  for (char c : port) l += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto ends = [&l](const char* suffix) {
    const std::string s(suffix);
    return l.size() > s.size() && l.compare(l.size() - s.size(), s.size(), s) == 0;
  };
  for (const char* s : {"_n", "_b", "_l", "_bar", "_n_i", "_ni", "_n_o", "_no", "reqn", "ackn"}) {
    if (ends(s)) return true;
  }
  return false;
}

}  // namespace

std::string failure_hint(const VerifyFailure& f, const ReceiverDescription& d, const std::vector<std::string>& held_at_zero) {
  // A stamp wrong while an input that reads as a time is held at 0: a design that stamps from a
  // time it is given.
  if (f.check == "timestamp" && !d.has("time_in")) {
    for (const std::string& name : held_at_zero) {
      std::string lower = name;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (lower.find("time") != std::string::npos || lower.find("ts") != std::string::npos) {
        return fmt::format("input {} is held at 0: a time the design stamps from is named time_in in [ports], and aesim "
                           "drives it with the ticks since the reset",
                           name);
      }
    }
  }
  // A handshake line named active low but described at the default, high: the design sees Req up
  // whenever the bus is idle, or Ack reads up as reset ends. Named before every other cause: the
  // rest of the run follows from it.
  if (f.check == "reset" || f.check.rfind("ack_", 0) == 0 || f.check == "handshake") {
    for (const char* role : {"req", "ack"}) {
      const auto port = d.ports.find(role);
      if (port != d.ports.end() && !port->second.joined() && d.active_high(role) && named_active_low(port->second.port)) {
        return fmt::format("{} port {} is named as active low but described active high: {} = {{ port = \"{}\", "
                           "active = \"low\" }}",
                           role, port->second.port, role, port->second.port);
      }
    }
  }
  // A two-phase link's lines rest where the reset leaves them, and the description says which level.
  if (f.check == "reset" && d.two_phase()) {
    return fmt::format("the lines of a two-phase link rest at their inactive level after reset, and aesim's Req starts "
                       "there: low by default, high with req and ack described {{ port = \"...\", active = \"low\" }} (the "
                       "description now has Ack rest {})",
                       d.active_high("ack") ? "low" : "high");
  }
  // A Req held through the reset answered late: a top that synchronises its own reset.
  if (f.check == "ack_rise_latency" && f.case_name == "req_through_reset") {
    return fmt::format("a design that passes its reset through flops of its own comes out of reset that many edges late: "
                       "reset = {{ ..., release_cycles = N }} says so (now {})",
                       d.reset_release_cycles);
  }
  // The collision case's beat: what a collided transaction gives is the description's policy.
  if (f.check == "beat" && f.case_name == "collision") {
    return fmt::format("what a collided transaction gives is behaviour.collisions (now \"{}\": \"discard\" no beat, "
                       "\"flag\" a beat with bit 0 of flags set, \"pass\" a beat of the OR address)",
                       to_string(d.collisions));
  }
  // The address taken after the sender let go of it (a receiver that reads it when Req falls).
  if (f.beat_of_released_lines && d.address_held == ReceiverDescription::AddressHeld::UntilAckRises) {
    return "the beat carries the address lines as they are once Ack has risen and the sender let go of them: a receiver "
           "takes the address while Req is high; a sender that holds it until Ack falls is described with "
           "[bus] address_held = \"until_ack_falls\"";
  }
  // A beat as Req fell: each edge of Req taken for a transaction.
  if (f.beat_as_req_fell && !d.two_phase()) {
    return "a beat where no transaction waited, as Req fell: the description's handshake is four-phase (Req rises and "
           "falls once for each event, Ack follows each edge), and a two-phase receiver, which takes each edge of Req "
           "for an event and changes Ack once, gives a second beat at the fall: [bus] handshake = \"two_phase\"";
  }
  // A beat with no transaction waiting: a valid read at the wrong level or as the wrong kind of
  // strobe, or an output word that is no event.
  if (f.check == "beat" && f.expected.rfind("no beat", 0) == 0) {
    return "a beat where no transaction waited: a valid active low (valid = { port = ..., active = \"low\" }), one held "
           "for each word (beat = \"rise\") or toggled for each (beat = \"change\"), and words that are no event "
           "(special = ...) are each said in the description";
  }
  return "";
}

}  // namespace aesim
