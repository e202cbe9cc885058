#pragma once
#include <algorithm>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "description/receiver_description.hpp"
#include "driver/dut_library.hpp"
#include "scoreboard/stamp_rule.hpp"

namespace aesim {

// What the receiver showed just before a rising clock edge, with the inputs that edge sees. With an
// output clock of its own (ReceiverDescription::has_out_clock) the receiver's edges carry the
// handshake and reset (`clock`) and the output clock's the output stream (`output`); else both.
struct EdgeSample {
  bool clock = true, output = true;
  bool reset = false, ready = true, valid = false, ack = false;
  bool special = false;  // the beat offered is no event (the description's `special` role)
  std::uint64_t out_addr = 0, timestamp = 0, flags = 0, overflow = 0;
};

struct VerifyFailure {
  std::string case_name, check, expected, observed;
  double time_s = 0;
  std::uint64_t cycle = 0;
  // A beat whose address is what the bus's address lines carry once the sender has let go of them
  // (Req low), not the transaction's: the receiver took the address after Ack rose.
  bool beat_of_released_lines = false;
  // A beat of the released lines where no transaction waited, soon after Req fell (within twice
  // the latency bound and two edges: an Ack and a registered valid after it): the receiver took
  // the fall for a transaction of its own (a two-phase receiver).
  bool beat_as_req_fell = false;
  // What a correct design that fails so first usually lacks in its description (failure_hint),
  // set by the command that has the whole description and the design's ports.
  std::string hint = {};
};

// Checks a receiver against its description alone, at the level of transactions: it sees the bus
// wires and the receiver's ports, never its insides.
//  - Every output beat is a transaction the bus carried, in bus order: an address (and contention
//    flag, per the collision policy) the wires held between Req rising and Ack rising, so nothing
//    is invented and nothing reordered. A beat may come before Ack rises or at the edge it rises
//    (a combinational valid); it belongs to the transaction then open. A transaction with no beat
//    is allowed only when the description says so: a collision under "discard", or a full output
//    under "drop" (the output was stalled around it), and then overflow_count, if present, must
//    have counted exactly the drops. A Req that falls before any Ack (a glitch) is not a
//    transaction: a receiver may ignore it, or (without a glitch filter) answer it within the
//    latency bound with an Ack that then falls as usual and perhaps a beat of the glitch's
//    address; the next transactions must go through as ever. A beat that says it is no event (the
//    description's `special` role: an in-band time marker) belongs to no transaction; it is
//    counted, and waits as any beat must.
//  - Stamps follow one rule for the run (StampRule), exactly, modulo the wrap.
//  - A beat offered and not taken (valid, not ready) stays, unchanged, until taken.
//  - The handshake: Ack rises only while Req is high and falls only after Req fell (four-phase
//    order). Latency counts the first rising edge after a change as 1: Ack rises no sooner than
//    ack_latency min edges after Req rose, and no later than ack_latency max edges after the later
//    of Req rising and the reset's release (a Req held through a reset is a transaction for the
//    receiver, whose synchroniser may or may not have been reset); under "hold" a rising Ack may
//    also wait while the output is stalled. Ack falls within the same bounds of Req falling. Ack
//    is low after a reset.
//  - On a two-phase link (ReceiverDescription::Handshake) a change of Req is its rise and a change
//    of Ack that answers it its Ack rising; Ack has no fall to check, and a change of Ack with no
//    change of Req waiting is an Ack without a Req.
//  - The RTL's own verdicts ($stop, $error, $fatal, failing assertions) fail the run.
class TransactionScoreboard {
 public:
  // Without a flags port every beat counts as unflagged; without overflow_count drops are
  // checked against the stalls alone.
  TransactionScoreboard(const ReceiverDescription& description, bool has_overflow, int overflow_width);

  void begin_case(const std::string& name);
  // The bus wires changed at t_ps, after `edges_done` rising edges of this case.
  void wires(std::uint64_t t_ps, std::uint64_t edges_done, bool req, std::uint64_t addr, bool contention);
  // Rising edge `cycle` at t_ps, with what stood before it; an output clock's edge is numbered by
  // the receiver's edges done before it.
  void edge(std::uint64_t cycle, std::uint64_t t_ps, const EdgeSample& s);
  // A design without a reset: Ack as its initial values left it, before the first edge.
  void power_up(bool ack);
  // Ack changed right after rising edge `cycle`.
  void ack_changed(std::uint64_t cycle, std::uint64_t t_ps, bool ack);
  // The RTL ended the case itself ($finish) or judged itself; a verdict is a failure.
  void rtl_event(std::uint64_t cycle, std::uint64_t t_ps, const RtlEvent& event);
  // The case is over: accounts for every transaction left (unless the RTL cut it short).
  void finish_case(std::uint64_t cycle, std::uint64_t t_ps, bool cut_short = false);

  std::uint64_t transactions() const { return transactions_; }
  std::uint64_t beats_checked() const { return beats_; }
  // Beats taken that said they were no event (the `special` role), not matched to transactions.
  std::uint64_t special_beats() const { return special_beats_; }
  std::uint64_t failures() const { return failures_; }
  std::uint64_t protocol_violations() const { return violations_; }
  std::uint64_t drops_accepted() const { return drops_total_; }
  const std::optional<VerifyFailure>& first_failure() const { return first_; }
  // The first failure of the case under way (since begin_case), beside the run's first: a design
  // that fails several cases usually fails each for its own reason.
  const std::optional<VerifyFailure>& case_first_failure() const { return case_first_; }
  // The stamp rule the beats followed, e.g. "ticks since reset at edge 4 after Req rose".
  std::string stamp_rule() const { return stamps_.describe(); }
  std::optional<StampRule::Candidate> stamp_edge() const { return stamps_.rule(); }
  // The Ack latencies the receiver showed, in edges as ack_latency_cycles counts them: rising for
  // transactions that met no full output and whose Req rose outside a reset, falling after every
  // Req but a glitch's. Empty (count 0) when none came.
  struct LatencySpan {
    std::uint64_t min = ~0ULL, max = 0, count = 0;
    void add(std::uint64_t edges) {
      min = std::min(min, edges);
      max = std::max(max, edges);
      ++count;
    }
  };
  const LatencySpan& ack_rise_latency() const { return rise_latency_; }
  const LatencySpan& ack_fall_latency() const { return fall_latency_; }
  void hold_stamps_to(const StampRule::Candidate& c) { stamps_.hold_to(c); }

 private:
  struct Transaction {
    std::uint64_t id = 0;
    std::uint64_t t_req = 0;
    std::uint64_t first_edge = 0;  // the first rising edge after Req rose: the lower latency bound's origin
    std::uint64_t bound_edge = 0;  // the later of that and the reset's release: the upper bound's origin
    std::uint64_t ack_edge = 0;
    std::optional<std::uint64_t> ack_fall_edge;  // once its Ack has fallen (a stamp may be taken then)
    bool acked = false, withdrawn = false, stalled = false;
    bool answered = false;                               // withdrawn (a glitch), yet the receiver raised Ack for it
    bool beat_taken = false;                             // its beat came before its Ack
    std::uint64_t beat_stamp = 0, beat_cycle = 0, beat_t_ps = 0;
    std::vector<std::pair<std::uint64_t, bool>> values;  // (addr, contention) held while open
  };
  struct Beat {
    std::uint64_t addr, ts;
    bool flag;
  };
  // The expected and observed texts of a failure, made only for the first one: a broken receiver
  // fails millions of checks, and formatting each would cost more than the run.
  using Texts = std::pair<std::string, std::string>;
  template <class Describe>
  void fail(const char* check, std::uint64_t cycle, std::uint64_t t_ps, bool protocol, Describe describe) {
    ++failures_;
    violations_ += protocol ? 1 : 0;
    if (case_first_) return;
    Texts texts = describe();
    case_first_ = VerifyFailure{case_, check, std::move(texts.first), std::move(texts.second),
                                static_cast<double>(t_ps) * 1e-12, cycle};
    if (!first_) first_ = case_first_;
  }
  // A word taken: an event's fields gathered from its words (event_words), then the event as a beat.
  void word(std::uint64_t cycle, std::uint64_t t_ps, const Beat& w, bool special);
  void beat(std::uint64_t cycle, std::uint64_t t_ps, const Beat& b);
  void check_stamp(const Transaction& t, std::uint64_t stamp, std::uint64_t cycle, std::uint64_t t_ps);
  bool value_matches(const Transaction& t, const Beat& b) const;
  bool may_lack_beat(const Transaction& t) const;
  void count_missing_beat(const Transaction& t);
  bool has_contention(const Transaction& t) const;
  std::string describe(const Transaction& t) const;
  void clear_for_reset();
  Transaction& open_transaction(std::uint64_t t_req, std::uint64_t first_edge, std::uint64_t bound_edge);

  ReceiverDescription::Collisions collisions_;
  ReceiverDescription::Full full_;
  bool has_overflow_, has_stamp_;
  std::uint64_t overflow_mask_;
  int lat_min_, lat_max_;
  // The design's own reset synchroniser: it acts on the bus this many edges after the release.
  std::uint64_t release_edges_;
  // A two-phase link, seen as the four-phase bus behind it: the driver reports each change of Ack
  // that answers a transaction as Ack rising, the sender letting go, and Ack falling at once.
  bool two_phase_;
  std::uint64_t acting_from_edge_ = 0;  // the first edge it may act on after the last reset
  StampRule stamps_;  // one rule for the whole run, across cases
  LatencySpan rise_latency_, fall_latency_;

  std::string case_;
  std::deque<Transaction> pending_;
  Transaction* open();  // the transaction whose Req is up and not yet acknowledged, if any
  std::optional<std::uint64_t> open_id_;
  std::uint64_t next_id_ = 0;
  std::optional<std::uint64_t> acked_id_;  // the transaction the Ack now high (or last high) answered
  bool req_ = false, ack_ = false, in_reset_ = false;
  std::uint64_t addr_ = 0, req_rise_edge_ = 0, req_rise_ps_ = 0;
  bool contention_ = false;
  std::uint64_t req_fall_edge_ = 0;  // first edge after Req fell, while Ack is due to fall
  bool ack_fall_due_ = false, late_reported_ = false, answered_glitch_ = false;
  std::optional<Beat> held_;  // offered, not taken, at the previous edge
  // An event of several output words: how many, the word each field comes from, the words taken so
  // far of the event under way and its fields from them.
  int event_words_ = 1, addr_word_ = 0, stamp_word_ = 0, flag_word_ = 0;
  int special_word_ = -1;  // the word whose mark makes the whole event no event; -1: marks are words of their own
  int words_taken_ = 0;
  Beat gathered_{0, 0, false};
  bool gathered_special_ = false;
  std::uint64_t last_stall_edge_ = 0;
  bool stalled_ever_ = false;
  std::uint64_t overflow_base_ = 0, overflow_now_ = 0;
  std::uint64_t drops_strict_ = 0, drops_maybe_ = 0;

  std::uint64_t transactions_ = 0, beats_ = 0, failures_ = 0, violations_ = 0, drops_total_ = 0, special_beats_ = 0;
  std::optional<VerifyFailure> first_, case_first_;
};

}  // namespace aesim
