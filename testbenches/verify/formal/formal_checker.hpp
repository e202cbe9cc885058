#pragma once
#include <optional>
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "scoreboard/stamp_rule.hpp"

namespace aesim {

// One property of the formal check: what it asserts, written from the description.
struct FormalProperty {
  int id;            // the checker's CHECK parameter selects it
  std::string name;  // e.g. "ack_rise_max"
  std::string text;  // what it asserts, in words
};

// The formal checker of a receiver (docs/reference.md section 6, --formal): a module aesim_formal_top that
// instantiates the team's top with the description's parameters (and its [formal] overrides; the
// description's [inputs] are taken as they are, so the caller applies [formal] inputs),
// drives its inputs from free inputs under the sender's assumptions, and asserts the description's
// promises. Each step of the proof is one clock edge; a reset is held for the first
// kFormalResetSteps steps.
//
// Assumed: the sender keeps the four-phase protocol (Req rises only while Ack is low and stays up
// until Ack rose; it is low during the reset), the address and contention are stable from Req
// rising to Ack rising, the [inputs] are held, the consumer's ready is free, and (for drops)
// overflow_count counts a drop by the edge its Ack rises.
// Asserted, each a property of its own: Ack low after reset; Ack rises only while a Req waits, no
// sooner than the lower latency bound and within the upper (or of the consumer's last stall, under
// "hold"); Ack falls only after Req fell, within the bounds; a beat offered and not taken holds;
// no beat is invented; the beat of a transaction the solver picks (a symbolic tag, so every
// transaction is covered without a model of the FIFO) comes in bus order with its address and
// flag by the collision policy; its stamp follows the stamp rule.
struct FormalChecker {
  std::string source;                      // aesim_formal.sv
  std::vector<FormalProperty> properties;  // in CHECK order
  int depth = 0;                           // steps of the bounded check
  std::string depth_reason;                // how the depth was derived
  std::vector<std::string> notes;          // properties left out, and why
};

inline constexpr int kFormalResetSteps = 4;

// `stamp`: the stamp rule to assert (stated, or inferred by the simulation); none leaves the stamp
// property out.
FormalChecker formal_checker(const ReceiverDescription& d, const std::vector<RtlPort>& ports,
                             const std::optional<StampRule::Candidate>& stamp);

}  // namespace aesim
