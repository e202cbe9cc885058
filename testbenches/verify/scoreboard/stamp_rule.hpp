#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "description/receiver_description.hpp"

namespace aesim {

// The one rule a receiver's stamps follow for a whole run (docs/reference.md section 6): the stamp of every
// transaction is ticks(p) mod 2^bits, the ticks completed since the last reset at one fixed edge p
// of the transaction, where
//   ticks(e) = floor((e - r) / N)  (0 for e <= r), e counting rising edges, r the last edge of the
//   reset, N the tick in clock cycles.
// The edge is fixed relative to one edge of the handshake: edge k after Req rose (the first edge
// after the rise is 1; k from 0, the edge before it, to ack_latency max + 1), or the edge Ack rose
// + j, or the edge Ack fell + j (j from -ack_latency max to +1: a receiver that stamps as it ends
// the handshake, with the address word out long before); on a two-phase link the edges where Req and
// Ack change, Ack once. A description may state k
// (timestamp_offset_cycles); otherwise every such edge is a candidate, and each beat keeps only the
// candidates that explain its stamp (one whose Ack has not fallen explains none of Ack's fall). A
// stamp that no remaining candidate explains fails; the candidates stay as they were, so each later
// beat is held to the same rule.
// A stamp a whole tick off can be told from a stamp taken at another edge only when the tick is
// longer than the window of candidate edges; stating the offset removes the doubt.
class StampRule {
 public:
  explicit StampRule(const ReceiverDescription& d);

  bool enabled() const { return enabled_; }
  // r above: the last edge of the latest reset.
  void reset_ended(std::uint64_t last_reset_edge) { origin_ = last_reset_edge; }

  // A transaction's edges: the first edge after Req rose (a range, for a Req held through a reset:
  // from the first edge after it rose to the first edge after the reset), the edge Ack rose, and
  // the edge it fell (none while it has not).
  struct Edges {
    std::uint64_t req_first = 0, req_last = 0, ack = 0;
    std::optional<std::uint64_t> ack_fall;
  };
  // True if some remaining candidate explains `stamp` (then only those remain); false, with what
  // the rule predicts in `expected`, if none does.
  bool check(const Edges& e, std::uint64_t stamp, std::string& expected);

  std::uint64_t ticks(std::uint64_t edge) const { return edge <= origin_ ? 0 : (edge - origin_) / tick_cycles_; }
  // The rule as inferred so far, e.g. "ticks at edge 4 after Req rose"; empty before any beat.
  std::string describe() const;

  // The edge of a stamp: offset k after Req rose (1 = the first edge after it), or the edge Ack
  // rose or fell + offset.
  enum class Anchor { ReqRise, AckRise, AckFall };
  struct Candidate {
    Anchor anchor;
    int offset;
  };
  // The first rule that explains every beat so far (the stated one if the description states it),
  // or none before any beat.
  std::optional<Candidate> rule() const;
  // Holds the stamps to this rule from the first beat (a replay of a run whose rule is known).
  void hold_to(const Candidate& c) {
    candidates_ = initial_ = {c};
    narrowed_ = true;
  }

 private:
  bool explains(const Candidate& c, const Edges& e, std::uint64_t stamp) const;
  // Candidate c's edge (the last of a range); none for Ack's fall before it fell.
  static std::optional<std::uint64_t> edge_of(const Candidate& c, const Edges& e);
  std::uint64_t predicted(const Candidate& c, const Edges& e) const;
  std::string name(const Candidate& c) const;

  bool enabled_;
  std::uint64_t tick_cycles_ = 1, mask_ = 0, origin_ = 0;
  bool two_phase_;  // Req's and Ack's edges are changes either way, and Ack changes once a transaction
  std::vector<Candidate> candidates_, initial_;
  bool narrowed_ = false;
};

}  // namespace aesim
