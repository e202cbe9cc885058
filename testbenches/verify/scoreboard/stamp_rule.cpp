#include "scoreboard/stamp_rule.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

namespace aesim {

StampRule::StampRule(const ReceiverDescription& d)
    : enabled_(d.has("timestamp")),
      tick_cycles_(d.timestamp_cycles ? d.timestamp_cycles : 1),
      mask_(d.timestamp_bits >= 64 ? ~0ULL : (1ULL << d.timestamp_bits) - 1),
      two_phase_(d.two_phase()) {
  if (d.timestamp_offset_cycles) {
    initial_.push_back({Anchor::ReqRise, *d.timestamp_offset_cycles});
  } else {
    for (int k = 0; k <= d.ack_latency_max + 1; ++k) initial_.push_back({Anchor::ReqRise, k});
    // A two-phase Ack changes once a transaction: its fall would be its rise again.
    for (const Anchor a : {Anchor::AckRise, Anchor::AckFall}) {
      if (a == Anchor::AckFall && two_phase_) continue;
      for (int j = -d.ack_latency_max; j <= 1; ++j) initial_.push_back({a, j});
    }
  }
  candidates_ = initial_;
}

std::string StampRule::name(const Candidate& c) const {
  if (c.anchor == Anchor::ReqRise) return fmt::format("edge {} after Req {}", c.offset, two_phase_ ? "changed" : "rose");
  const char* edge = two_phase_ ? "the edge Ack changed" : c.anchor == Anchor::AckRise ? "the edge Ack rose" : "the edge Ack fell";
  if (c.offset == 0) return edge;
  return fmt::format("{} {} {}", edge, c.offset < 0 ? "-" : "+", std::abs(c.offset));
}

namespace {

std::uint64_t at(std::uint64_t edge, int offset) {
  const auto shifted = static_cast<std::int64_t>(edge) + offset;
  return shifted < 0 ? 0 : static_cast<std::uint64_t>(shifted);
}

}  // namespace

std::optional<std::uint64_t> StampRule::edge_of(const Candidate& c, const Edges& e) {
  switch (c.anchor) {
    case Anchor::ReqRise: return at(e.req_last, c.offset - 1);
    case Anchor::AckRise: return at(e.ack, c.offset);
    case Anchor::AckFall: break;
  }
  if (!e.ack_fall) return std::nullopt;
  return at(*e.ack_fall, c.offset);
}

// The edges of candidate c: one edge, or a range when Req rose during a reset.
bool StampRule::explains(const Candidate& c, const Edges& e, std::uint64_t stamp) const {
  const std::optional<std::uint64_t> hi = edge_of(c, e);
  if (!hi) return false;
  const std::uint64_t lo = c.anchor == Anchor::ReqRise ? at(e.req_first, c.offset - 1) : *hi;
  const std::uint64_t t_lo = ticks(lo), t_hi = ticks(*hi);
  return t_hi - t_lo >= mask_ || ((stamp - t_lo) & mask_) <= t_hi - t_lo;
}

std::uint64_t StampRule::predicted(const Candidate& c, const Edges& e) const {
  return ticks(edge_of(c, e).value_or(0)) & mask_;
}

bool StampRule::check(const Edges& e, std::uint64_t stamp, std::string& expected) {
  std::vector<Candidate> kept;
  for (const Candidate& c : candidates_) {
    if (explains(c, e, stamp)) kept.push_back(c);
  }
  if (!kept.empty()) {
    narrowed_ = true;
    candidates_ = std::move(kept);
    return true;
  }
  if (narrowed_) {
    const Candidate& c = candidates_.front();
    expected = fmt::format("stamp {} (ticks since reset at {}, the rule of the earlier beats)", predicted(c, e), name(c));
  } else {
    // The span of the candidates' edges, of those that have come.
    std::uint64_t lo = ~0ULL, hi = 0;
    for (const Candidate& c : candidates_) {
      if (!edge_of(c, e)) continue;
      lo = std::min(lo, predicted(c, e));
      hi = std::max(hi, predicted(c, e));
    }
    expected = two_phase_ ? fmt::format("a stamp from {} to {} (ticks since reset at an edge from Req changing to Ack "
                                        "changing)", lo, hi)
                          : fmt::format("a stamp from {} to {} (ticks since reset at an edge from Req rising to Ack {})",
                                        lo, hi, e.ack_fall ? "falling" : "rising");
  }
  return false;
}

std::string StampRule::describe() const {
  if (!enabled_ || !narrowed_) return "";
  std::string text = "ticks since reset at " + name(candidates_.front());
  for (std::size_t i = 1; i < candidates_.size(); ++i) text += " or " + name(candidates_[i]);
  return text;
}

}  // namespace aesim

namespace aesim {

std::optional<StampRule::Candidate> StampRule::rule() const {
  if (!enabled_) return std::nullopt;
  if (narrowed_ || initial_.size() == 1) return candidates_.front();
  return std::nullopt;
}

}  // namespace aesim
