#include "driver/case_driver.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <utility>

#include "aesim/bus/wired_or_lines.hpp"
#include "aesim/random/splitmix64.hpp"
#include "scoreboard/stamp_rule.hpp"

namespace aesim {

std::uint64_t clock_period_ps(const ReceiverDescription& d) {
  // Even, so that the falling edge lies exactly half-way (also in an exported testbench).
  return std::max<std::uint64_t>(2, 2 * static_cast<std::uint64_t>(std::llround(0.5e12 / d.clock_hz)));
}

OutClock out_clock_of(const ReceiverDescription& d, const VerifyCase& c) {
  OutClock o;
  if (!d.has_out_clock()) return o;
  // The case's own draws: its seed and its name (the directed cases share one seed).
  std::uint64_t name_hash = 0xCBF29CE484222325ULL;
  for (const char ch : c.name) name_hash = (name_hash ^ static_cast<unsigned char>(ch)) * 0x100000001B3ULL;
  SplitMix64 draw = stream_for(c.seed ^ name_hash, Stream::VerifyClockPhase, 0);
  // Evenly in the logarithm of the frequency over a range (a decade's each part alike).
  const double u = uniform01(draw);
  o.hz = d.out_clock_hz_max > d.out_clock_hz ? d.out_clock_hz * std::pow(d.out_clock_hz_max / d.out_clock_hz, u) : d.out_clock_hz;
  o.period_ps = std::max<std::uint64_t>(4, 4 * static_cast<std::uint64_t>(std::llround(0.25e12 / o.hz)));
  // Its edges, and its consumer's changes a quarter period after its rises, never fall on the
  // receiver's edges: at one instant the run takes the receiver's edge first (and its inputs'
  // changes then, recorded after it), where a simulator takes both at once (each side's flops
  // seeing the other's values from before), and an exported testbench would part from the run.
  // They meet the receiver's edges only at multiples of g = gcd(its period, the receiver's half
  // period) from its first rise, so a first rise whose fall and quarter are off those multiples
  // too never meets one; a period a few picoseconds longer makes g at least 4, so that one exists.
  const std::uint64_t half = clock_period_ps(d) / 2;
  while (std::gcd(o.period_ps, half) < 4) o.period_ps += 4;
  const std::uint64_t g = std::gcd(o.period_ps, half);
  const auto meets = [&](std::uint64_t rise) {
    return rise % g == 0 || (rise + o.period_ps / 2) % g == 0 || (rise + o.period_ps / 4) % g == 0;
  };
  // Anywhere in its first period, but never at time 0, with the inputs still being set.
  o.first_rise_ps = 1 + draw() % (o.period_ps - 1);
  while (meets(o.first_rise_ps)) o.first_rise_ps = o.first_rise_ps % (o.period_ps - 1) + 1;
  o.hz = 1e12 / static_cast<double>(o.period_ps);
  return o;
}

namespace {

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

// The pixel side of the bus (the cycle rung's wired-OR lines, or a queue of senders taking turns)
// and the wires it drives, with any glitch on top. The senders let go of Req when Ack rises; the
// address and contention go with it, or (a sender that holds them until Ack falls) stay until then.
// On a two-phase link the bus behind it is the same four-phase bus (what the scoreboard is told),
// and its edge towards the receiver a toggle: Req changes where the bus's Req rises (outside the
// receiver's reset), and the driver turns each change of Ack that answers it into Ack rising and
// falling at once.
class BusSide {
 public:
  BusSide(const VerifyCase& c, const BoundPorts& ports, const ReceiverDescription& d, TransactionScoreboard* sb,
          std::vector<WaveRecord>* wave)
      : queued_(c.queued_senders),
        hold_(d.address_held == ReceiverDescription::AddressHeld::UntilAckFalls),
        two_phase_(d.two_phase()),
        ports_(ports),
        sb_(sb),
        wave_(wave) {}

  void fire(std::uint32_t addr, bool ack, std::uint64_t t, std::uint64_t edges_done, CaseStats& stats) {
    ++stats.firings;
    if (queued_ && (req_ || ack || !waiting_.empty())) {
      waiting_.push_back(addr);
      return;
    }
    if (!lines_.join(addr, addr, ack)) {
      ++stats.absorbed;
      return;
    }
    drive(t, edges_done);
  }
  void glitch(bool on, std::uint32_t addr, std::uint64_t t, std::uint64_t edges_done) {
    glitch_ = on;
    glitch_addr_ = addr;
    drive(t, edges_done);
  }
  void ack_changed(bool ack, std::uint64_t t, std::uint64_t edges_done) {
    if (ack) {
      if (hold_ && lines_.req()) {
        held_ = true;
        held_addr_ = lines_.addr();
        held_contention_ = lines_.contention();
      }
      lines_.release(released_);
      drive(t, edges_done);
      return;
    }
    const bool was_held = held_;
    held_ = false;
    if (queued_ && !waiting_.empty() && !lines_.req()) {
      lines_.join(waiting_.front(), waiting_.front(), false);
      waiting_.pop_front();
      drive(t, edges_done);
    } else if (was_held) {
      drive(t, edges_done);
    }
  }
  // Wires as a recorded run drove them (a formal counterexample), not from pixels.
  void force(bool req, std::uint64_t addr, bool contention, std::uint64_t t, std::uint64_t edges_done) {
    forced_ = true;
    forced_req_ = req;
    forced_addr_ = addr;
    forced_contention_ = contention;
    drive(t, edges_done);
  }
  bool quiet() const { return !lines_.req() && waiting_.empty() && !glitch_; }
  bool req() const { return req_; }
  void record_controls(std::uint64_t t, bool ready, bool reset) {
    ready_ = ready;
    if (two_phase_ && reset != reset_) {
      // The link's sender is reset with the receiver; a transaction the bus still holds open is
      // asked for again as the reset ends.
      const bool phase = !reset && req_;
      if (phase != phase_) {
        phase_ = phase;
        ports_.set_req(phase_);
      }
    }
    reset_ = reset;
    record(t);
  }
  // A change of Ack on a two-phase link: whether it answers the change of Req waiting (the lines
  // differed before it); in the receiver's reset it answers nothing.
  bool ack_changed_on_link(bool ack_line) {
    const bool answers = !reset_ && phase_ != ack_line_;
    ack_line_ = ack_line;
    return answers;
  }
  bool ack_line() const { return ack_line_; }

 private:
  void drive(std::uint64_t t, std::uint64_t edges_done) {
    // While Ack is high no pixel joins (one that fires sees Ack and withdraws), so held lines are
    // the released transaction's alone.
    const std::uint64_t lines = held_ ? held_addr_ : lines_.addr();
    const std::uint64_t addr = forced_ ? forced_addr_ : lines | (glitch_ ? glitch_addr_ : 0);
    const bool req = forced_ ? forced_req_ : lines_.req() || glitch_;
    const bool contention = forced_ ? forced_contention_ : held_ ? held_contention_ : lines_.contention();
    if (req == req_ && addr == addr_ && contention == contention_) return;
    if (two_phase_ && req && !req_ && !reset_) phase_ = !phase_;
    req_ = req;
    addr_ = addr;
    contention_ = contention;
    ports_.set_req(two_phase_ ? phase_ : req);
    ports_.addr.write(addr);
    ports_.set_contention(contention);
    if (sb_) sb_->wires(t, edges_done, req, addr, contention);
    record(t);
  }
  void record(std::uint64_t t) {
    if (wave_) wave_->push_back({t, two_phase_ ? phase_ : req_, contention_, ready_, reset_, addr_});
  }

  bool queued_;
  bool hold_;
  bool two_phase_;
  bool phase_ = false, ack_line_ = false;  // a two-phase link's Req line and the Ack line last seen
  bool held_ = false, held_contention_ = false;  // holding the last transaction's lines until Ack falls
  std::uint32_t held_addr_ = 0;
  const BoundPorts& ports_;
  TransactionScoreboard* sb_;
  std::vector<WaveRecord>* wave_;
  WiredOrLines<std::uint32_t> lines_;  // the pixels driving, by address
  std::vector<std::uint32_t> released_;  // those the last Ack released (storage reused)
  std::deque<std::uint32_t> waiting_;
  bool glitch_ = false;
  std::uint32_t glitch_addr_ = 0;
  bool forced_ = false, forced_req_ = false, forced_contention_ = false;
  std::uint64_t forced_addr_ = 0;
  bool req_ = false, contention_ = false, ready_ = true, reset_ = true;
  std::uint64_t addr_ = 0;
};

// The output stream before a rising edge that takes it: a beat by the description's rule (valid's
// level, its rise or its change since the edge before, `valid_was`), with its fields.
void sample_output(const BoundPorts& ports, ReceiverDescription::ValidBeat rule, bool& valid_was, EdgeSample& s) {
  const bool valid_now = ports.valid_raised();
  switch (rule) {
    case ReceiverDescription::ValidBeat::High: s.valid = valid_now; break;
    case ReceiverDescription::ValidBeat::Rise: s.valid = valid_now && !valid_was; break;
    case ReceiverDescription::ValidBeat::Change: s.valid = valid_now != valid_was; break;
  }
  valid_was = valid_now;
  if (s.valid) {
    s.out_addr = ports.out_addr.read();
    s.timestamp = ports.timestamp.read();
    s.flags = ports.flags.read();
    s.special = ports.special_raised();
  }
  s.overflow = ports.overflow.read();
}

}  // namespace

CaseStats run_case(DutInstance& dut, const BoundPorts& ports, const ReceiverDescription& d, const VerifyCase& c,
                   TransactionScoreboard* sb, const CaseRunOptions& options) {
  const std::uint64_t period = clock_period_ps(d), half = period / 2;
  auto off_edge = [half](std::uint64_t t) { return t % half == 0 ? t + 1 : t; };
  CaseStats stats;
  BusSide bus(c, ports, d, sb, options.waveform);
  if (sb) sb->begin_case(c.name);

  std::unique_ptr<FiringSource> source = c.make_firings ? c.make_firings() : nullptr;
  Firing next;
  bool have_next = source && source->next(next);
  if (have_next) next.t_ps = off_edge(next.t_ps);
  // Glitch starts and ends, in time order.
  struct GlitchEdge {
    std::uint64_t t;
    bool on;
    std::uint32_t addr;
  };
  std::vector<GlitchEdge> glitch_edges;
  for (const ReqGlitch& g : c.glitches) {
    glitch_edges.push_back({off_edge(g.from_ps), true, g.addr});
    glitch_edges.push_back({off_edge(g.to_ps), false, g.addr});
  }
  std::sort(glitch_edges.begin(), glitch_edges.end(), [](const GlitchEdge& a, const GlitchEdge& b) { return a.t < b.t; });
  std::size_t gi = 0;

  SplitMix64 ready_rng = stream_for(c.seed, Stream::VerifyReady, 0);
  // Ready with probability p: the top 53 bits of a draw below p * 2^53 (uniform01 < p, in integers).
  const bool always_ready = c.ready_probability >= 1;
  const auto ready_below = static_cast<std::uint64_t>(std::max(0.0, c.ready_probability) * 0x1.0p53);
  // A design without a reset starts from its initial values, never in reset.
  const std::uint64_t reset_edges = d.has_reset() ? kResetEdges : 0;
  bool ready = true, reset = d.has_reset(), ack = false, draining = false;
  // A two-phase link (its Ack line as last seen is the bus's): `ack` is the four-phase Ack of the
  // bus behind it, high from the change that answered its Req until that Req falls (at once, where
  // the pixels let go of it as they see the answer; a replayed sender may hold it longer).
  const bool two_phase = d.two_phase();
  auto end_answer = [&](std::uint64_t edge, std::uint64_t t_ps) {
    if (!two_phase || !ack || bus.req()) return;
    ack = false;
    if (sb) sb->ack_changed(edge, t_ps, false);
    bus.ack_changed(false, t_ps + 1, edge);
  };
  std::uint64_t acks = 0, reset_from = kNever, quiet = 0;
  bool valid_was = false;  // valid at the edge before (a beat on its rise: ReceiverDescription)
  std::uint64_t stalls_end = 0;
  for (const auto& s : c.stalls) stalls_end = std::max(stalls_end, s.second);
  const std::uint64_t quiet_needed = 2 * static_cast<std::uint64_t>(d.ack_latency_max) + 8;

  // Bus changes due before t_limit, in time order, after `edges_done` rising edges.
  auto apply_until = [&](std::uint64_t t_limit, std::uint64_t edges_done) {
    bool changed = false;
    for (;;) {
      const std::uint64_t tf = have_next ? next.t_ps : kNever;
      const std::uint64_t tg = gi < glitch_edges.size() ? glitch_edges[gi].t : kNever;
      if (std::min(tf, tg) >= t_limit) return changed;
      if (tg <= tf) {
        bus.glitch(glitch_edges[gi].on, glitch_edges[gi].addr, tg, edges_done);
        ++gi;
      } else {
        bus.fire(next.addr, ack, tf, edges_done, stats);
        have_next = source->next(next);
        if (have_next) next.t_ps = std::max(off_edge(next.t_ps), tf);
      }
      changed = true;
    }
  };
  // The time a design reads (time_in): after edge e, the ticks completed since the reset by the
  // stamps' own rule (StampRule::ticks, from the design's release, its own release_cycles after
  // aesim's), modulo 2^timestamp_bits.
  const bool drives_time = d.has("time_in");
  const std::uint64_t time_mask = d.timestamp_bits >= 64 ? ~0ULL : (1ULL << d.timestamp_bits) - 1;
  StampRule time_rule(d);
  bool time_in_reset = d.has_reset();
  auto set_time = [&](std::uint64_t k, bool reset_k) {
    if (reset_k) {
      time_in_reset = true;
    } else if (time_in_reset) {
      time_in_reset = false;
      time_rule.reset_ended(k - 1 + static_cast<std::uint64_t>(d.reset_release_cycles));
    }
    ports.time_in.write(time_in_reset ? 0 : time_rule.ticks(k - 1) & time_mask);
  };
  // The consumer's ready for the output's next edge, receiver edge k the next to come (stalls count
  // the receiver's edges).
  auto ready_at = [&](std::uint64_t k) {
    if (!c.replay.empty()) return k - 1 < c.replay.size() ? c.replay[k - 1].ready : true;
    if (draining) return true;
    const bool stalled = std::any_of(c.stalls.begin(), c.stalls.end(), [k](const auto& s) { return k >= s.first && k < s.second; });
    return !stalled && (always_ready || (ready_rng() >> 11) < ready_below);
  };
  // The consumer and the reset for rising edge k, set a quarter period after edge k-1 (before
  // the falling edge, so that one evaluation takes them with it); with an output clock of its own,
  // the consumer follows that clock instead (out_step).
  const bool out_clock = d.has_out_clock();
  auto set_controls = [&](std::uint64_t k) {
    const bool ready_k = out_clock ? ready : ready_at(k);
    const bool reset_k = k <= reset_edges || (k >= reset_from && k < reset_from + static_cast<std::uint64_t>(c.reset_edges));
    if (drives_time) set_time(k, reset_k);
    if (ready_k == ready && reset_k == reset) return;
    ready = ready_k;
    reset = reset_k;
    ports.set_ready(ready);
    ports.set_reset(reset);
    bus.record_controls((k - 1) * period + half / 2, ready, reset);
  };

  // The output side's own clock: rising edges at out_rise + j * out_period; a quarter period after
  // each, the consumer's ready for the next; half a period after it, the falling edge.
  const OutClock out_clock_timing = out_clock_of(d, c);
  const std::uint64_t out_period = out_clock_timing.period_ps;
  std::uint64_t out_next = out_clock ? out_clock_timing.first_rise_ps : kNever;
  enum class OutEdge { Rise, Ready, Fall } out_due = OutEdge::Rise;
  bool out_valid_was = false, out_beat = false;
  auto out_step = [&](std::uint64_t edges_done) {
    const std::uint64_t t = out_next;
    const bool trace_now = options.trace && edges_done >= options.trace_from && edges_done <= options.trace_to;
    switch (out_due) {
      case OutEdge::Rise: {
        dut.eval();
        EdgeSample s;
        s.clock = false;
        s.reset = reset;
        s.ready = ready;
        sample_output(ports, d.valid_beat, out_valid_was, s);
        if (sb) sb->edge(edges_done, t, s);
        out_beat = out_beat || s.valid;
        if (options.beats && s.valid && ready && !reset) options.beats->push_back({s.out_addr, s.timestamp, s.flags & 1, s.special});
        ports.set_out_clk(true);
        dut.eval();
        if (trace_now) dut.dump(t);
        out_next = t + out_period / 4;
        out_due = OutEdge::Ready;
        break;
      }
      case OutEdge::Ready: {
        const bool ready_next = ready_at(edges_done + 1);
        if (ready_next != ready) {
          ready = ready_next;
          ports.set_ready(ready);
          bus.record_controls(t, ready, reset);
        }
        out_next = t + out_period / 4;
        out_due = OutEdge::Fall;
        break;
      }
      case OutEdge::Fall:
        ports.set_out_clk(false);
        dut.eval();
        if (trace_now) dut.dump(t);
        out_next = t + out_period / 2;
        out_due = OutEdge::Rise;
        break;
    }
  };
  // The output clock's events before t_limit, each after the bus's changes before it; out of line,
  // so that a run without such a clock keeps its per-edge loop small (about 4 % faster in
  // receiver_rate_bench than with it inline).
  auto out_steps_until = [&](std::uint64_t t_limit, std::uint64_t edges_done) __attribute__((noinline)) {
    while (out_next < t_limit) {
      apply_until(out_next, edges_done);
      out_step(edges_done);
    }
    return true;
  };
  // Bus changes and the output clock's events before t_limit, in time order; true when some input
  // changed since the last evaluation.
  auto advance_until = [&](std::uint64_t t_limit, std::uint64_t edges_done) {
    const bool stepped = out_next < t_limit && out_steps_until(t_limit, edges_done);
    return apply_until(t_limit, edges_done) || stepped;
  };

  ports.set_clk(false);
  ports.set_out_clk(false);
  ports.set_req(false);
  ports.addr.write(0);
  ports.set_contention(false);
  ports.set_ready(true);
  ports.set_reset(reset);
  if (drives_time) set_time(1, reset);
  bus.record_controls(0, true, reset);
  if (!c.replay.empty()) {
    ready = c.replay[0].ready;
    ports.set_ready(ready);
    bus.record_controls(half / 2, ready, reset);
    bus.force(c.replay[0].req, c.replay[0].addr, c.replay[0].contention, half / 2, 0);
  }
  advance_until(half, 0);
  dut.eval();
  if (sb && !d.has_reset()) sb->power_up(ports.ack_raised());

  // After every evaluation: has the RTL ended the case itself?
  auto rtl_ended = [&](std::uint64_t at) {
    if (dut.status() == 0) return false;
    stats.rtl = dut.event();
    if (sb) sb->rtl_event(at, at * period, stats.rtl);
    return true;
  };

  std::uint64_t k = 1;
  bool ended = rtl_ended(0);
  for (; k <= c.max_edges && !ended; ++k) {
    const std::uint64_t t_edge = k * period;
    if (advance_until(t_edge, k - 1)) dut.eval();  // changes in the second half of the cycle
    if ((ended = rtl_ended(k - 1))) break;

    EdgeSample s;
    s.output = !out_clock;
    s.reset = reset;
    s.ready = ready;
    s.ack = two_phase ? bus.ack_line() : ack;
    if (out_clock) {
      s.overflow = ports.overflow.read();  // the output's own edges take its beats
    } else {
      sample_output(ports, d.valid_beat, valid_was, s);
    }
    if (sb) sb->edge(k, t_edge, s);
    if (options.beats && s.valid && ready && !reset) options.beats->push_back({s.out_addr, s.timestamp, s.flags & 1, s.special});

    ports.set_clk(true);
    dut.eval();
    const bool trace_now = options.trace && k >= options.trace_from && k <= options.trace_to;
    if (trace_now) dut.dump(t_edge);
    if ((ended = rtl_ended(k))) break;
    const bool ack_now = ports.ack_raised();
    if (two_phase && ack_now != bus.ack_line()) {
      const bool answers = bus.ack_changed_on_link(ack_now);
      if (sb) sb->ack_changed(k, t_edge, true);
      if (answers) {
        ack = true;
        if (++acks == static_cast<std::uint64_t>(c.reset_after_ack) && c.reset_after_ack > 0) {
          reset_from = k + static_cast<std::uint64_t>(c.reset_delay);
        }
        bus.ack_changed(true, t_edge + 1, k);
        end_answer(k, t_edge);
      } else if (!ack && sb) {
        sb->ack_changed(k, t_edge, false);
      }
    } else if (!two_phase && ack_now != ack) {
      ack = ack_now;
      if (sb) sb->ack_changed(k, t_edge, ack);
      if (ack && ++acks == static_cast<std::uint64_t>(c.reset_after_ack) && c.reset_after_ack > 0) {
        reset_from = k + static_cast<std::uint64_t>(c.reset_delay);
      }
      bus.ack_changed(ack, t_edge + 1, k);
    }

    const bool reset_over = c.reset_after_ack == 0 || (reset_from != kNever && k >= reset_from + static_cast<std::uint64_t>(c.reset_edges));
    if (!have_next && gi == glitch_edges.size() && bus.quiet() && reset_over && k >= stalls_end && k >= c.replay.size()) {
      draining = true;
    }
    if (draining) {
      // A beat at this edge, or (with an output clock of its own) at one of the output's since the last.
      const bool beat = out_clock ? std::exchange(out_beat, false) : s.valid;
      quiet = (!beat && !ack && !bus.req()) ? quiet + 1 : 0;
      if (quiet > quiet_needed) break;
    }

    // The consumer and the reset change a quarter period after the edge, amid the bus's own
    // changes, so that the waveform stays in time order.
    advance_until(t_edge + half / 2, k);
    set_controls(k + 1);
    if (k < c.replay.size()) {
      const ReplayStep& step = c.replay[k];
      bus.force(step.req, step.addr, step.contention, t_edge + half / 2, k);
      end_answer(k, t_edge);
    }
    advance_until(t_edge + half, k);
    ports.set_clk(false);
    dut.eval();
    if (trace_now) dut.dump(t_edge + half);
    if ((ended = rtl_ended(k))) break;
  }
  stats.edges = std::min(k, c.max_edges);
  stats.rtl_output = dut.take_output();
  if (sb) sb->finish_case(stats.edges, stats.edges * period, ended);
  return stats;
}

}  // namespace aesim
