#include "aesim/receiver/reference_clock_domain.hpp"

#include <algorithm>

namespace aesim {

ReferenceClockDomain::ReferenceClockDomain(const sc_core::sc_module_name& name, ReceiverSignals& s,
                                           const Clock& clock, const ReceiverCycleModel::Config& config,
                                           StreamConsumer consumer)
    : sc_module(name),
      s_(s),
      clock_(clock),
      period_ps_(clock.period.value()),
      ts_mask_(clock.ts_width >= 64 ? ~0ULL : (1ULL << clock.ts_width) - 1),
      fifo_limit_(config.fifo_limit),
      ts_external_(config.ts_external),
      model_(config),
      outputs_(&model_.outputs()),
      consumer_(std::move(consumer)) {
  clock_.prescale = std::max(1u, clock_.prescale);
  SC_METHOD(on_wake);
}

// Defined before on_wake, inline: they run at every edge.
inline StreamView ReferenceClockDomain::view() const {
  StreamView v;
  v.valid = out().valid;
  v.ready = ready_;
  v.flags = out().beat.flags;
  v.ts = static_cast<std::uint32_t>(out().beat.ts);
  v.addr = out().beat.addr;
  v.events = static_cast<std::uint32_t>(out().events);
  v.fifo_count = out().fifo_count;
  v.fifo_limit = fifo_limit_;
  return v;
}

inline bool ReferenceClockDomain::stops_after_edge() {
  // GatedClock stops at the falling edge when the receiver is idle with Req low. An idle receiver
  // holds Ack low, so Req cannot fall before then; if it rises before the next rising edge, that
  // edge comes next either way: so stopping at once, until Req rises, gives the same edges.
  if (!out().idle || req() || k_ * period_ps_ + period_ps_ / 2 < clock_.free_running_until.value()) {
    return false;
  }
  running_ = false;
  next_trigger(s_.req.posedge_event());
  return true;
}

// Edges come one after the next while the clock runs, so the quotient is counted on instead of a
// 64-bit division at every edge (the RTL in the cycle rung 2-3 % faster, 9.4-9.7 -> 9.7-9.9 M
// edges/s, event_rate_bench's BM_CycleLetterA_Rtl, three interleaved runs of each build). After a
// stop the clock restarts at any edge: divided again.
inline std::uint64_t ReferenceClockDomain::stamp_at_edge() {
  if (k_ == stamp_edge_ + 1 && stamp_edge_ != 0) {
    if (++stamp_remainder_ == clock_.prescale) {
      stamp_remainder_ = 0;
      ++stamp_quotient_;
    }
  } else {
    stamp_quotient_ = k_ / clock_.prescale;
    stamp_remainder_ = k_ % clock_.prescale;
  }
  stamp_edge_ = k_;
  return stamp_quotient_ & ts_mask_;
}

inline void ReferenceClockDomain::step_edge() {
  ++edges_;
  // Everything latched here sees the values held before the edge.
  const StreamView before = view();
  rules_.edge(before);
  const bool ready = ready_;
  ready_ = consumer_.edge(before.valid, before.ready, before.ts, before.addr, before.flags);
  ReceiverCycleModel::Inputs in;
  in.req = req();
  in.addr = released_ ? 0 : s_.addr.read();
  in.contention = !released_ && s_.contention.read();
  in.ready = ready;
  if (stepped_) {
    // The RTL has the timestamp port whatever its setting, as on a tile's wires.
    stepped_->clock(in, stamp_at_edge());
    return;
  }
  // Only an external timestamp is read.
  if (ts_external_) in.ts = stamp_at_edge();
  model_.clock(in);
}

void ReferenceClockDomain::on_wake() {
  const std::uint64_t now = sc_core::sc_time_stamp().value();
  // The kernel has moved on since the last activation: the wires show what the bus did.
  released_ = false;
  if (!running_) {
    if (!s_.req.read() && now >= clock_.free_running_until.value()) {
      next_trigger(s_.req.posedge_event());
      return;
    }
    // Started (at t = 0 with a free-running clock) or restarted by Req: the first edge strictly
    // after now comes next.
    running_ = true;
    k_ = now / period_ps_ + 1;
  } else {
    // Woken at edge k_: stepped now, unless it was stepped ahead and only its outputs wait for
    // their time.
    if (!stepped_ahead_) step_edge();
    stepped_ahead_ = false;
    released_ = out().ack && !s_.ack.read();
    s_.overflows.write(static_cast<std::uint32_t>(out().overflows));
    s_.ack.write(out().ack);
    if (stops_after_edge()) return;
    ++k_;
  }
  // The wires stay as they are (released, when Ack rose at this edge) until the tile's next
  // firing joins them: the edges before then are stepped here, without the kernel, up to the
  // first one whose outputs the bus must see at their time.
  const std::uint64_t horizon = wires_hold_until_ ? wires_hold_until_() : now;
  while (k_ * period_ps_ <= horizon) {
    const bool ack = out().ack;
    const std::uint64_t overflows = out().overflows;
    step_edge();
    if (out().ack != ack || out().overflows != overflows) {
      stepped_ahead_ = true;
      break;
    }
    if (stops_after_edge()) return;
    ++k_;
  }
  next_trigger(sc_core::sc_time::from_value(k_ * period_ps_ - now));
}

std::uint64_t ReferenceClockDomain::violations() const { return rules_.violations(view()); }

}  // namespace aesim
