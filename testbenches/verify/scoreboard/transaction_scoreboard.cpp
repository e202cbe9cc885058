#include "scoreboard/transaction_scoreboard.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace aesim {

using Collisions = ReceiverDescription::Collisions;
using Full = ReceiverDescription::Full;

TransactionScoreboard::TransactionScoreboard(const ReceiverDescription& d, bool has_overflow, int overflow_width)
    : collisions_(d.collisions),
      full_(d.full),
      has_overflow_(has_overflow),
      has_stamp_(d.has("timestamp")),
      overflow_mask_(overflow_width >= 64 ? ~0ULL : (1ULL << overflow_width) - 1),
      lat_min_(d.ack_latency_min),
      lat_max_(d.ack_latency_max),
      release_edges_(static_cast<std::uint64_t>(d.reset_release_cycles)),
      two_phase_(d.two_phase()),
      stamps_(d),
      event_words_(d.event_words),
      addr_word_(d.word("out_addr")),
      stamp_word_(d.word("timestamp")),
      flag_word_(d.word("flags")),
      special_word_(d.special_word.value_or(-1)) {}

void TransactionScoreboard::begin_case(const std::string& name) {
  case_ = name;
  case_first_.reset();
  clear_for_reset();
  req_ = ack_ = in_reset_ = contention_ = false;
  addr_ = req_rise_edge_ = req_rise_ps_ = acting_from_edge_ = 0;
  stamps_.reset_ended(0);
  last_stall_edge_ = 0;
  stalled_ever_ = false;
  overflow_base_ = overflow_now_ = 0;
  drops_strict_ = drops_maybe_ = 0;
}

TransactionScoreboard::Transaction* TransactionScoreboard::open() {
  if (!open_id_ || pending_.empty() || *open_id_ < pending_.front().id) return nullptr;
  return &pending_[*open_id_ - pending_.front().id];
}

TransactionScoreboard::Transaction& TransactionScoreboard::open_transaction(std::uint64_t t_req, std::uint64_t first_edge,
                                                                            std::uint64_t bound_edge) {
  Transaction t;
  t.id = next_id_++;
  t.t_req = t_req;
  t.first_edge = first_edge;
  t.bound_edge = bound_edge;
  t.values.push_back({addr_, contention_});
  pending_.push_back(std::move(t));
  open_id_ = pending_.back().id;
  late_reported_ = false;
  return pending_.back();
}

std::string TransactionScoreboard::describe(const Transaction& t) const {
  std::string values;
  for (const auto& [a, c] : t.values) values += fmt::format("{}0x{:x}{}", values.empty() ? "" : " or ", a, c ? " (contention)" : "");
  return fmt::format("the transaction of Req at {:.6f} us: address {}", static_cast<double>(t.t_req) * 1e-6, values);
}

bool TransactionScoreboard::has_contention(const Transaction& t) const {
  return std::any_of(t.values.begin(), t.values.end(), [](const auto& v) { return v.second; });
}

bool TransactionScoreboard::value_matches(const Transaction& t, const Beat& b) const {
  for (const auto& [a, c] : t.values) {
    if (a != b.addr) continue;
    switch (collisions_) {
      case Collisions::Discard:
        if (!c && !b.flag) return true;
        break;
      case Collisions::Flag:
        if (b.flag == c) return true;
        break;
      case Collisions::Pass:
        if (!b.flag) return true;
        break;
    }
  }
  return false;
}

bool TransactionScoreboard::may_lack_beat(const Transaction& t) const {
  if (t.withdrawn) return true;
  if (collisions_ == Collisions::Discard && has_contention(t)) return true;
  return full_ == Full::Drop && t.stalled;
}

// A transaction allowed to give no beat: a glitch counts nothing; a discarded collision is no
// drop, unless the output was full then too (a receiver may count it either way); else a drop.
void TransactionScoreboard::count_missing_beat(const Transaction& t) {
  if (t.withdrawn) return;
  if (collisions_ == Collisions::Discard && has_contention(t)) {
    drops_maybe_ += full_ == Full::Drop && t.stalled ? 1 : 0;
  } else {
    ++drops_strict_;
  }
}

void TransactionScoreboard::clear_for_reset() {
  pending_.clear();
  open_id_.reset();
  acked_id_.reset();
  held_.reset();
  words_taken_ = 0;
  gathered_special_ = false;
  ack_fall_due_ = late_reported_ = answered_glitch_ = false;
}

void TransactionScoreboard::wires(std::uint64_t t_ps, std::uint64_t edges_done, bool req, std::uint64_t addr,
                                  bool contention) {
  const bool rose = req && !req_, fell = !req && req_;
  req_ = req;
  addr_ = addr;
  contention_ = contention;
  if (rose) {
    req_rise_edge_ = edges_done + 1;
    req_rise_ps_ = t_ps;
  }
  if (in_reset_) return;
  if (rose) {
    // A Req that rises while the design's own reset synchroniser still holds it is answered from
    // the edge it comes out.
    open_transaction(t_ps, edges_done + 1, std::max(edges_done + 1, acting_from_edge_));
    return;
  }
  Transaction* t = open();
  if (fell) {
    if (t) {
      t->withdrawn = true;  // Req fell before any Ack: a glitch, not a transaction
      open_id_.reset();
    } else if (ack_) {
      ack_fall_due_ = true;
      req_fall_edge_ = edges_done + 1;
      late_reported_ = false;
    }
    return;
  }
  if (req && t && (t->values.back().first != addr || t->values.back().second != contention)) {
    t->values.push_back({addr, contention});
  }
}

void TransactionScoreboard::power_up(bool ack) {
  if (ack) fail("reset", 0, 0, true, [] { return Texts{"Ack low at power-up (the design has no reset)", "Ack high"}; });
}

void TransactionScoreboard::edge(std::uint64_t cycle, std::uint64_t t_ps, const EdgeSample& s) {
  // Most edges of a run: no beat offered or held, no Ack awaited, no reset. Nothing to check.
  const bool awaiting_ack = !late_reported_ && (open_id_ || ack_fall_due_);
  if (!s.valid && !held_ && !awaiting_ack && !s.reset && !in_reset_) {
    overflow_now_ = s.overflow;
    return;
  }
  if (s.clock && s.reset) {
    if (!in_reset_) clear_for_reset();
    in_reset_ = true;
    return;
  }
  if (!s.clock && in_reset_) {
    overflow_now_ = s.overflow;
    return;
  }
  if (in_reset_) {
    in_reset_ = false;
    // The design's reset ends release_edges_ later than aesim's, where its own synchroniser lets go.
    acting_from_edge_ = cycle + release_edges_;
    stamps_.reset_ended(cycle - 1 + release_edges_);
    overflow_base_ = s.overflow;
    drops_strict_ = drops_maybe_ = 0;
    if (s.ack) fail("reset", cycle, t_ps, true, [&] { return Texts{"Ack low after reset", "Ack high"}; });
    ack_ = s.ack;
    // A Req held through the reset is a new transaction for the receiver: the lower latency
    // bound counts from its rise, the upper from the first edge the receiver may act on.
    if (req_) open_transaction(req_rise_ps_, std::min(req_rise_edge_, cycle), acting_from_edge_);
  }
  overflow_now_ = s.overflow;
  // The output stream: a beat offered, taken or held, and a consumer's stall.
  if (s.output) {
    // A beat offered and not taken must wait, unchanged.
    if (held_) {
      const Beat now{s.out_addr, s.timestamp, (s.flags & 1) != 0};
      if (!s.valid) {
        fail("stalled_output", cycle, t_ps, false, [&] {
          return Texts{fmt::format("valid held with address 0x{:x}", held_->addr), "valid fell"};
        });
      } else if (now.addr != held_->addr || now.ts != held_->ts || now.flag != held_->flag) {
        fail("stalled_output", cycle, t_ps, false, [&] {
          return Texts{fmt::format("address 0x{:x} stamp {} flag {}", held_->addr, held_->ts, held_->flag),
                       fmt::format("address 0x{:x} stamp {} flag {}", now.addr, now.ts, now.flag)};
        });
      }
    }
    held_.reset();
    if (s.valid) {
      const Beat b{s.out_addr, s.timestamp, (s.flags & 1) != 0};
      if (s.ready && s.special && special_word_ < 0) {
        ++special_beats_;  // no event: no transaction to match, though it waited as any beat does
      } else if (s.ready) {
        word(cycle, t_ps, b, s.special);
      } else {
        held_ = b;
        last_stall_edge_ = cycle;
        stalled_ever_ = true;
      }
    }

    // Under "hold" a receiver with no room of its own (its valid follows ready) waits for ready with
    // nothing offered: a consumer not ready while a transaction waits for its Ack excuses the wait too.
    if (full_ == Full::Hold && !s.ready && !s.valid && open()) {
      last_stall_edge_ = cycle;
      stalled_ever_ = true;
    }
  }
  if (!s.clock) return;

  // Ack overdue: reported at the first edge past the bound, once per change.
  if (!late_reported_) {
    if (Transaction* t = open(); t && req_ && !ack_) {
      std::uint64_t start = t->bound_edge;
      if (full_ == Full::Hold && stalled_ever_ && last_stall_edge_ + 1 > start) start = last_stall_edge_ + 1;
      if (cycle >= start && cycle - start + 1 > static_cast<std::uint64_t>(lat_max_)) {
        late_reported_ = true;
        fail("ack_rise_latency", cycle, t_ps, true, [&] {
          return Texts{fmt::format(two_phase_ ? "Ack changed within {} edges of Req changing" : "Ack within {} edges of Req rising",
                                   lat_max_),
                       fmt::format("no Ack after {} edges", cycle - start + 1)};
        });
      }
    } else if (ack_fall_due_ && cycle - req_fall_edge_ + 1 > static_cast<std::uint64_t>(lat_max_)) {
      late_reported_ = true;
      fail("ack_fall_latency", cycle, t_ps, true, [&] {
        return Texts{fmt::format("Ack low within {} edges of Req falling", lat_max_),
                     fmt::format("Ack still high after {} edges", cycle - req_fall_edge_ + 1)};
      });
    }
  }
}

void TransactionScoreboard::ack_changed(std::uint64_t cycle, std::uint64_t t_ps, bool ack) {
  ack_ = ack;
  if (in_reset_) return;
  if (ack) {
    Transaction* t = open();
    if (!req_ && !t && !pending_.empty()) {
      // Ack answering a Req that fell before it (a glitch): a receiver without a glitch filter
      // took the pulse for a request. Allowed, if it came within the latency bound of that Req;
      // Ack must then fall as after any Req, and a beat of the glitch's address may follow.
      Transaction& glitch = pending_.back();
      if (glitch.withdrawn && !glitch.answered &&
          cycle - glitch.bound_edge + 1 <= static_cast<std::uint64_t>(lat_max_)) {
        glitch.answered = true;
        glitch.ack_edge = cycle;
        acked_id_ = glitch.id;
        glitch.values.push_back({addr_, contention_});  // the wires as the receiver latched them
        ack_fall_due_ = true;
        answered_glitch_ = true;
        req_fall_edge_ = cycle + 1;
        late_reported_ = false;
        if (glitch.beat_taken) {
          const Transaction done = glitch;
          pending_.pop_back();
          check_stamp(done, done.beat_stamp, done.beat_cycle, done.beat_t_ps);
        }
        return;
      }
    }
    if (!req_ || !t) {
      fail("ack_without_req", cycle, t_ps, true, [&] {
        return two_phase_ ? Texts{"Ack changes only while a change of Req waits for it", "Ack changed with none waiting"}
                          : Texts{"Ack rises only while Req is high", "Ack rose with Req low"};
      });
      return;
    }
    const std::uint64_t latency = cycle - t->first_edge + 1;
    std::uint64_t start = t->bound_edge;
    if (full_ == Full::Hold && stalled_ever_ && last_stall_edge_ + 1 > start) start = last_stall_edge_ + 1;
    const std::uint64_t excused = cycle >= start ? cycle - start + 1 : 1;
    if (!late_reported_ && (latency < static_cast<std::uint64_t>(lat_min_) || excused > static_cast<std::uint64_t>(lat_max_))) {
      fail("ack_rise_latency", cycle, t_ps, true, [&] {
        return Texts{fmt::format("{} to {} edges", lat_min_, lat_max_), fmt::format("{} edges", latency)};
      });
    }
    t->acked = true;
    t->ack_edge = cycle;
    acked_id_ = t->id;
    // Met a full output: the output stalled within a few edges before the Req (a receiver may
    // decide on fullness a pipeline stage or two early) or while waiting for the Ack.
    t->stalled = stalled_ever_ && last_stall_edge_ + static_cast<std::uint64_t>(lat_max_) + 8 >= t->first_edge;
    if (!t->stalled && t->bound_edge == t->first_edge) rise_latency_.add(latency);
    open_id_.reset();
    ++transactions_;
    late_reported_ = false;
    if (t->beat_taken) {
      // Its beat came first (at this edge, or earlier): the stamp is checked now the Ack is known.
      const Transaction done = *t;
      pending_.erase(pending_.begin() + static_cast<long>(t->id - pending_.front().id));
      check_stamp(done, done.beat_stamp, done.beat_cycle, done.beat_t_ps);
    }
    return;
  }
  if (req_) {
    fail("ack_fell_with_req", cycle, t_ps, true, [&] {
      return Texts{"Ack falls only after Req fell (four-phase order)", "Ack fell with Req high"};
    });
    return;
  }
  // The edge the transaction's Ack fell, for a stamp taken there (its beat still to come).
  if (acked_id_) {
    // Nearly always the newest: searched from the back.
    for (auto t = pending_.rbegin(); t != pending_.rend(); ++t) {
      if (t->id == *acked_id_) {
        t->ack_fall_edge = cycle;
        break;
      }
    }
    acked_id_.reset();
  }
  // A two-phase Ack's one change answered the transaction; the driver ends it at once.
  if (ack_fall_due_ && !two_phase_) {
    const std::uint64_t latency = cycle - req_fall_edge_ + 1;
    if (!answered_glitch_) fall_latency_.add(latency);
    const bool early = latency < static_cast<std::uint64_t>(lat_min_) && !answered_glitch_;
    if (!late_reported_ && (early || latency > static_cast<std::uint64_t>(lat_max_))) {
      fail("ack_fall_latency", cycle, t_ps, true, [&] {
        return Texts{fmt::format("{} to {} edges", lat_min_, lat_max_), fmt::format("{} edges", latency)};
      });
    }
  }
  ack_fall_due_ = false;
  answered_glitch_ = false;
  late_reported_ = false;
}

void TransactionScoreboard::check_stamp(const Transaction& t, std::uint64_t stamp, std::uint64_t cycle, std::uint64_t t_ps) {
  if (!has_stamp_) return;
  const StampRule::Edges edges{t.first_edge, t.bound_edge, t.ack_edge, t.ack_fall_edge};
  std::string expected;
  if (stamps_.check(edges, stamp, expected)) return;
  fail("timestamp", cycle, t_ps, false, [&] { return Texts{expected + " for " + describe(t), fmt::format("{}", stamp)}; });
}

void TransactionScoreboard::word(std::uint64_t cycle, std::uint64_t t_ps, const Beat& w, bool special) {
  if (event_words_ == 1 && special_word_ < 0) return beat(cycle, t_ps, w);
  if (words_taken_ == addr_word_) gathered_.addr = w.addr;
  if (words_taken_ == stamp_word_) gathered_.ts = w.ts;
  if (words_taken_ == flag_word_) gathered_.flag = w.flag;
  if (words_taken_ == special_word_) gathered_special_ = special;
  if (++words_taken_ < event_words_) return;
  words_taken_ = 0;
  if (gathered_special_) {
    ++special_beats_;  // an event's shape that says it is none (a timestamp wrap)
    gathered_special_ = false;
    return;
  }
  beat(cycle, t_ps, gathered_);
}

void TransactionScoreboard::beat(std::uint64_t cycle, std::uint64_t t_ps, const Beat& b) {
  ++beats_;
  auto matches = [&](const Transaction& t) {
    return !t.beat_taken && (!t.withdrawn || t.answered) && value_matches(t, b);
  };
  std::size_t i = 0;
  while (i < pending_.size() && !matches(pending_[i]) && may_lack_beat(pending_[i])) ++i;
  if (i == pending_.size() && !pending_.empty()) {
    // A beat of a glitch the receiver is answering at this very edge (its valid follows the
    // synchronised Req): the wires as it read them; its Ack must follow at once.
    Transaction& glitch = pending_.back();
    if (glitch.withdrawn && !glitch.answered && !glitch.beat_taken &&
        cycle - glitch.bound_edge + 1 <= static_cast<std::uint64_t>(lat_max_)) {
      glitch.values.push_back({addr_, contention_});
      if (value_matches(glitch, b)) {
        for (std::size_t k = 0; k + 1 < pending_.size(); ++k) count_missing_beat(pending_[k]);
        pending_.erase(pending_.begin(), pending_.end() - 1);
        Transaction& t = pending_.front();
        t.beat_taken = true;
        t.beat_stamp = b.ts;
        t.beat_cycle = cycle;
        t.beat_t_ps = t_ps;
        return;
      }
      glitch.values.pop_back();
    }
  }
  if (i == pending_.size() || !matches(pending_[i])) {
    const Transaction* head = nullptr;
    for (const Transaction& t : pending_) {
      if (!t.withdrawn && !t.beat_taken) {
        head = &t;
        break;
      }
    }
    fail("beat", cycle, t_ps, false, [&] {
      return Texts{head ? describe(*head) : "no beat (no transaction is waiting)",
                   fmt::format("address 0x{:x}, stamp {}, flag {}", b.addr, b.ts, b.flag ? 1 : 0)};
    });
    if (failures_ == 1 && head && head->acked && !req_ && b.addr == addr_ && !value_matches(*head, b)) {
      first_->beat_of_released_lines = true;
    }
    // Of the lines as they are after the fall (a valid held over several edges repeats its word).
    if (failures_ == 1 && !head && !req_ && b.addr == addr_ && req_fall_edge_ > 0 && cycle + 1 >= req_fall_edge_ &&
        cycle + 1 - req_fall_edge_ <= 2 * static_cast<std::uint64_t>(lat_max_) + 2) {
      first_->beat_as_req_fell = true;
    }
    return;
  }
  for (std::size_t k = 0; k < i; ++k) count_missing_beat(pending_[k]);
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(i));
  Transaction& t = pending_.front();
  if (!t.acked && !t.answered) {
    // The beat of the open transaction, before (or at the edge of) its Ack: it stays open.
    t.beat_taken = true;
    t.beat_stamp = b.ts;
    t.beat_cycle = cycle;
    t.beat_t_ps = t_ps;
    return;
  }
  const Transaction done = t;
  pending_.pop_front();
  check_stamp(done, b.ts, cycle, t_ps);
}

void TransactionScoreboard::rtl_event(std::uint64_t cycle, std::uint64_t t_ps, const RtlEvent& e) {
  if (e.kind == RtlEvent::Kind::None || e.kind == RtlEvent::Kind::Finish) return;
  const bool own = e.kind == RtlEvent::Kind::Stop;
  fail(own ? "rtl_assertion" : "rtl_error", cycle, t_ps, false, [&] {
    return Texts{own ? "no $stop, $error, $fatal or failing assertion in the RTL" : "a model Verilator can run",
                 e.message.empty() ? e.where : e.message};
  });
}

void TransactionScoreboard::finish_case(std::uint64_t cycle, std::uint64_t t_ps, bool cut_short) {
  if (in_reset_ || cut_short) {
    pending_.clear();
    return;
  }
  for (const Transaction& t : pending_) {
    if (t.withdrawn && t.beat_taken && !t.answered) {
      fail("ack_without_beat", cycle, t_ps, true, [&] {
        return Texts{"an Ack with the beat of " + describe(t), "a beat, and no Ack"};
      });
      continue;
    }
    if (!t.acked && !t.withdrawn) continue;  // never acknowledged: the latency check reported it
    if (!may_lack_beat(t)) {
      fail("lost", cycle, t_ps, false, [&] { return Texts{describe(t) + " gives a beat", "no beat"}; });
      continue;
    }
    count_missing_beat(t);
  }
  pending_.clear();
  drops_total_ += drops_strict_;
  if (has_overflow_) {
    // A counter of w bits counts modulo 2^w (an 8-bit one reads 164 after 1188 drops), or stops
    // at its largest value: a designer's narrow counter does either, and both are correct.
    const std::uint64_t counted = (overflow_now_ - overflow_base_) & overflow_mask_;
    const std::uint64_t most = drops_strict_ + drops_maybe_;
    const bool wrapped = drops_maybe_ >= overflow_mask_ || ((counted - drops_strict_) & overflow_mask_) <= drops_maybe_;
    const bool saturated = overflow_now_ == overflow_mask_ && overflow_base_ + most >= overflow_mask_;
    if (!wrapped && !saturated) {
      fail("overflow_count", cycle, t_ps, false, [&] {
        std::string expected = drops_maybe_ ? fmt::format("{} to {} drops counted", drops_strict_, most)
                                            : fmt::format("{} drops counted", drops_strict_);
        if (most > overflow_mask_) {
          expected += fmt::format(" (modulo 2^{} as the port is wide, or {} held at its largest)",
                                  64 - __builtin_clzll(overflow_mask_), overflow_mask_);
        }
        return Texts{expected, fmt::format("{}", counted)};
      });
    }
  }
}

}  // namespace aesim
