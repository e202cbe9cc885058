// The transaction scoreboard on hand-written bus histories: what it must accept and what it must
// catch, with no RTL at all.
#include <gtest/gtest.h>

#include <memory>

#include "scoreboard/transaction_scoreboard.hpp"

namespace aesim {
namespace {

constexpr std::uint64_t kPeriod = 20000;  // 50 MHz in ps

ReceiverDescription description(ReceiverDescription::Collisions collisions = ReceiverDescription::Collisions::Discard,
                                ReceiverDescription::Full full = ReceiverDescription::Full::Drop) {
  ReceiverDescription d;
  d.collisions = collisions;
  d.full = full;
  d.ports["timestamp"] = PortRef{"ts"};
  d.timestamp_tick = 1e-6;
  d.timestamp_cycles = 50;
  d.timestamp_bits = 8;
  d.ack_latency_min = 2;
  d.ack_latency_max = 3;
  return d;
}

// Drives the scoreboard edge by edge: reset on edges 1..4, then what each test scripts.
class History {
 public:
  explicit History(const ReceiverDescription& d, bool overflow = false) : sb(d, overflow, 8) {
    sb.begin_case("hand");
    for (int i = 0; i < 4; ++i) edge(true);
  }
  void edge(bool reset = false) {
    ++k;
    s.reset = reset;
    sb.edge(k, k * kPeriod, s);
  }
  void wires(bool req, std::uint64_t addr, bool contention = false) {
    sb.wires(k * kPeriod + kPeriod / 3, k, req, addr, contention);
  }
  void ack(bool a) {
    s.ack = a;
    sb.ack_changed(k, k * kPeriod, a);
  }
  // A clean transaction: Req after edge k, Ack rising `latency` edges later, Req released at
  // once, Ack falling `latency` edges later.
  void transaction(std::uint64_t addr, int latency = 2, bool contention = false) {
    wires(true, addr, contention);
    for (int i = 0; i < latency; ++i) edge();
    ack(true);
    sb.wires(k * kPeriod + 1, k, false, 0, false);
    for (int i = 0; i < latency; ++i) edge();
    ack(false);
  }
  void offer(std::uint64_t addr, std::uint64_t ts, bool flag = false) {
    s.valid = true;
    s.out_addr = addr;
    s.timestamp = ts;
    s.flags = flag ? 1 : 0;
  }
  void idle_output() { s.valid = false; }

  TransactionScoreboard sb;
  EdgeSample s;
  std::uint64_t k = 0;
};

TEST(TransactionScoreboard, AcceptsACleanTransactionAndItsBeat) {
  History h(description());
  for (int i = 0; i < 46; ++i) h.edge();  // edge 50: 1 us after the reset's last edge (4)
  h.transaction(0x2A5);
  h.offer(0x2A5, 0);  // stamped within a tick of the Req at 46 cycles = 0.92 us
  h.edge();
  h.idle_output();
  h.edge();
  h.sb.finish_case(h.k, h.k * kPeriod);
  EXPECT_EQ(h.sb.failures(), 0u) << h.sb.first_failure()->check;
  EXPECT_EQ(h.sb.transactions(), 1u);
  EXPECT_EQ(h.sb.beats_checked(), 1u);
}

TEST(TransactionScoreboard, CatchesAWrongAddressAStaleStampAndALostBeat) {
  {
    History h(description());
    h.transaction(0x2A5);
    h.offer(0x2A4, 0);
    h.edge();
    EXPECT_EQ(h.sb.first_failure()->check, "beat");
  }
  {
    History h(description());
    for (int i = 0; i < 200; ++i) h.edge();  // 4 us after reset
    h.transaction(0x001);
    h.offer(0x001, 1);  // two ticks early
    h.edge();
    EXPECT_EQ(h.sb.first_failure()->check, "timestamp");
  }
  {
    History h(description());
    h.transaction(0x001);
    h.edge();
    h.sb.finish_case(h.k, h.k * kPeriod);
    EXPECT_EQ(h.sb.first_failure()->check, "lost");
  }
}

TEST(TransactionScoreboard, CatchesHandshakeViolations) {
  {
    History h(description());
    h.edge();
    h.ack(true);  // no Req at all
    EXPECT_EQ(h.sb.first_failure()->check, "ack_without_req");
    EXPECT_EQ(h.sb.protocol_violations(), 1u);
  }
  {
    History h(description());
    h.wires(true, 0x10);
    h.edge();
    h.ack(true);  // after 1 edge; the description says 2 to 3
    EXPECT_EQ(h.sb.first_failure()->check, "ack_rise_latency");
  }
  {
    History h(description());
    h.wires(true, 0x10);
    for (int i = 0; i < 4; ++i) h.edge();  // the 4th edge finds no Ack: too late
    EXPECT_EQ(h.sb.first_failure()->check, "ack_rise_latency");
  }
  {
    History h(description());
    h.wires(true, 0x10);
    h.edge();
    h.edge();
    h.ack(true);
    h.edge();
    h.ack(false);  // Req still high
    EXPECT_EQ(h.sb.first_failure()->check, "ack_fell_with_req");
  }
}

TEST(TransactionScoreboard, AGlitchMayBeIgnoredOrAnsweredButAckMustStillFall) {
  auto glitch = [](History& h) {
    h.edge();
    h.wires(true, 0x155);
    h.sb.wires(h.k * kPeriod + kPeriod / 2, h.k, false, 0, false);  // Req falls within the cycle
  };
  {  // answered 2 edges later (within the bound), Ack falls 2 edges after that: fine
    History h(description());
    glitch(h);
    h.edge();
    h.edge();
    h.ack(true);
    h.edge();
    h.edge();
    h.ack(false);
    h.sb.finish_case(h.k, h.k * kPeriod);
    EXPECT_EQ(h.sb.failures(), 0u) << h.sb.first_failure()->check;
  }
  {  // answered, but Ack never falls
    History h(description());
    glitch(h);
    h.edge();
    h.edge();
    h.ack(true);
    for (int i = 0; i < 4; ++i) h.edge();
    ASSERT_TRUE(h.sb.first_failure());
    EXPECT_EQ(h.sb.first_failure()->check, "ack_fall_latency");
  }
  {  // an Ack long after the glitch answers nothing
    History h(description());
    glitch(h);
    for (int i = 0; i < 6; ++i) h.edge();
    h.ack(true);
    ASSERT_TRUE(h.sb.first_failure());
    EXPECT_EQ(h.sb.first_failure()->check, "ack_without_req");
  }
}

TEST(TransactionScoreboard, CollisionsFollowTheDeclaredPolicy) {
  using C = ReceiverDescription::Collisions;
  {  // discard: no beat is right, a beat is invented
    History quiet(description(C::Discard));
    quiet.transaction(0x0FF, 2, true);
    quiet.edge();
    quiet.sb.finish_case(quiet.k, quiet.k * kPeriod);
    EXPECT_EQ(quiet.sb.failures(), 0u);
    History noisy(description(C::Discard));
    noisy.transaction(0x0FF, 2, true);
    noisy.offer(0x0FF, 0, true);
    noisy.edge();
    EXPECT_EQ(noisy.sb.first_failure()->check, "beat");
  }
  {  // flag: the beat must carry the flag
    History flagged(description(C::Flag));
    flagged.transaction(0x0FF, 2, true);
    flagged.offer(0x0FF, 0, true);
    flagged.edge();
    EXPECT_EQ(flagged.sb.failures(), 0u);
    History unflagged(description(C::Flag));
    unflagged.transaction(0x0FF, 2, true);
    unflagged.offer(0x0FF, 0, false);
    unflagged.edge();
    EXPECT_EQ(unflagged.sb.first_failure()->check, "beat");
  }
}

// Transactions while the output is stalled with a beat (0x001): each of the `dropped` after it
// is dropped, and the overflow counter reads `counted` when the beat is taken.
std::unique_ptr<History> drops_while_stalled(std::uint64_t dropped, std::uint64_t counted) {
  auto h = std::make_unique<History>(description(), true);
  h->transaction(0x001);
  h->offer(0x001, 0);
  h->s.ready = false;
  h->edge();
  for (std::uint64_t i = 0; i < dropped; ++i) h->transaction(0x002 + i % 7);
  h->s.overflow = counted;
  h->s.ready = true;
  h->edge();  // 0x001 taken
  h->idle_output();
  h->edge();
  h->sb.finish_case(h->k, h->k * kPeriod);
  return h;
}

TEST(TransactionScoreboard, DropsNeedAStalledOutputAndAnExactCount) {
  // One dropped: the overflow counter must say 1.
  EXPECT_EQ(drops_while_stalled(1, 1)->sb.failures(), 0u);
  EXPECT_EQ(drops_while_stalled(1, 0)->sb.first_failure()->check, "overflow_count");
  // Without a stall, a missing beat is a loss whatever the counter says.
  History h(description(), true);
  h.transaction(0x001);
  h.s.overflow = 1;
  h.edge();
  h.sb.finish_case(h.k, h.k * kPeriod);
  EXPECT_EQ(h.sb.first_failure()->check, "lost");
}

// An 8-bit drop counter after 300 drops reads 44 if it wraps (300 - 256) and 255 if it stops at
// its largest value; both are correct hardware. 43 or 254 is a miscount, named with both readings.
TEST(TransactionScoreboard, ANarrowDropCounterMayWrapOrSaturate) {
  for (const std::uint64_t counted : {44u, 255u}) EXPECT_EQ(drops_while_stalled(300, counted)->sb.failures(), 0u) << counted;
  for (const std::uint64_t counted : {43u, 254u}) {
    const auto h = drops_while_stalled(300, counted);
    ASSERT_EQ(h->sb.failures(), 1u) << counted;
    EXPECT_EQ(h->sb.first_failure()->check, "overflow_count");
    EXPECT_EQ(h->sb.first_failure()->expected, "300 drops counted (modulo 2^8 as the port is wide, or 255 held at its largest)");
    EXPECT_EQ(h->sb.first_failure()->observed, std::to_string(counted));
  }
}

// docs/reference.md section 6, timing around a reset: the lower latency bound counts from Req rising, the upper
// from the later of Req rising and the reset's release (here edge 5, after reset on edges 1..4).
TEST(TransactionScoreboard, AReqHeldThroughResetIsTimedFromItsRiseAndFromTheRelease) {
  auto held = [](std::uint64_t rise_after_edge) {
    auto h = std::make_unique<History>(description());
    h->k = rise_after_edge;
    h->wires(true, 0x13C);
    h->k = 4;
    return h;
  };
  {  // Req rose after edge 1; Ack on edge 5, the first after the release: 4 edges after the rise
    auto h = held(1);
    h->edge();
    h->ack(true);
    h->sb.wires(h->k * kPeriod + 1, h->k, false, 0, false);
    h->offer(0x13C, 0);
    h->edge();
    h->idle_output();
    h->edge();
    h->ack(false);
    h->sb.finish_case(h->k, h->k * kPeriod);
    EXPECT_EQ(h->sb.failures(), 0u) << h->sb.first_failure()->check << ": " << h->sb.first_failure()->observed;
    EXPECT_EQ(h->sb.transactions(), 1u);
  }
  {  // Req rose after edge 4: Ack on edge 5 is 1 edge after it, under the lower bound of 2
    auto h = held(4);
    h->edge();
    h->ack(true);
    ASSERT_TRUE(h->sb.first_failure());
    EXPECT_EQ(h->sb.first_failure()->check, "ack_rise_latency");
    EXPECT_EQ(h->sb.first_failure()->observed, "1 edges");
  }
  {  // Req rose after edge 1: no Ack by edge 7, 3 edges after the release: late
    auto h = held(1);
    for (int i = 0; i < 3; ++i) h->edge();
    EXPECT_FALSE(h->sb.first_failure());
    h->edge();
    ASSERT_TRUE(h->sb.first_failure());
    EXPECT_EQ(h->sb.first_failure()->check, "ack_rise_latency");
  }
}

// docs/reference.md section 6: a beat taken at the edge where Ack rises (a valid that follows the synchronised
// Req) belongs to that transaction, as does one taken before it.
TEST(TransactionScoreboard, ABeatOnOrBeforeTheAckEdgeBelongsToItsTransaction) {
  for (int before : {0, 1}) {
    History h(description());
    h.wires(true, 0x2A5);
    h.edge();
    if (before) {
      h.offer(0x2A5, 0);
      h.edge();
      h.idle_output();
    } else {
      h.offer(0x2A5, 0);
      h.edge();  // the beat is taken at this edge, and Ack rises at it
      h.idle_output();
      h.ack(true);
    }
    if (before) h.ack(true);
    h.sb.wires(h.k * kPeriod + 1, h.k, false, 0, false);
    h.edge();
    h.edge();
    h.ack(false);
    h.sb.finish_case(h.k, h.k * kPeriod);
    EXPECT_EQ(h.sb.failures(), 0u) << before << ": " << h.sb.first_failure()->check << " " << h.sb.first_failure()->observed;
    EXPECT_EQ(h.sb.transactions(), 1u);
    EXPECT_EQ(h.sb.beats_checked(), 1u);
  }
}

// One stamp rule for the run: here ticks (50 cycles each) at the edge Ack rises. A stamp one tick
// stale fails, with what the rule predicts; the beats after it are held to the same rule.
TEST(TransactionScoreboard, StampsFollowOneRuleAndOneTickStaleFails) {
  History h(description());
  std::uint64_t stale_at = 0;
  for (int n = 0; n < 12; ++n) {
    for (int i = 0; i < 13; ++i) h.edge();
    h.transaction(0x10 + n);
    const std::uint64_t ack_edge = h.k - 2;  // transaction(): Ack on the 2nd edge, down 2 edges later
    std::uint64_t stamp = (ack_edge - 4) / 50;
    if (n == 8) {
      stamp -= 1;
      stale_at = h.k + 1;
    }
    h.offer(0x10 + n, stamp);
    h.edge();
    h.idle_output();
  }
  ASSERT_TRUE(h.sb.first_failure());
  EXPECT_EQ(h.sb.failures(), 1u);
  EXPECT_EQ(h.sb.first_failure()->check, "timestamp");
  EXPECT_EQ(h.sb.first_failure()->cycle, stale_at);
  EXPECT_NE(h.sb.first_failure()->expected.find("the rule of the earlier beats"), std::string::npos);
  EXPECT_NE(h.sb.stamp_rule().find("Ack"), std::string::npos) << h.sb.stamp_rule();
}

// A description may state the edge: then a stamp taken at another edge fails even on its first beat
// (here the stamp of edge 2 after Req rose, across a tick boundary, where the description says 1).
TEST(TransactionScoreboard, AStatedOffsetIsHeldFromTheFirstBeat) {
  for (int stated : {2, 1}) {
    ReceiverDescription d = description();
    d.timestamp_offset_cycles = stated;
    History h(d);
    for (int i = 0; i < 48; ++i) h.edge();  // Req after edge 52: its first edge, 53, is tick 0; edge 54 is tick 1
    h.transaction(0x33);
    h.offer(0x33, 1);
    h.edge();
    if (stated == 2) {
      EXPECT_EQ(h.sb.failures(), 0u) << h.sb.first_failure()->expected;
    } else {
      ASSERT_TRUE(h.sb.first_failure());
      EXPECT_EQ(h.sb.first_failure()->check, "timestamp");
    }
  }
}

TEST(TransactionScoreboard, TheRtlsOwnVerdictsFailAndItsFinishDoesNot) {
  History h(description());
  RtlEvent finish;
  finish.kind = RtlEvent::Kind::Finish;
  finish.where = "rx.v:9";
  h.sb.rtl_event(h.k, h.k * kPeriod, finish);
  EXPECT_EQ(h.sb.failures(), 0u);
  RtlEvent stop;
  stop.kind = RtlEvent::Kind::Stop;
  stop.where = "rx.v:12";
  stop.message = "rx.v:12: Assertion failed in rx: boom";
  h.sb.rtl_event(h.k, h.k * kPeriod, stop);
  ASSERT_TRUE(h.sb.first_failure());
  EXPECT_EQ(h.sb.first_failure()->check, "rtl_assertion");
  EXPECT_EQ(h.sb.first_failure()->observed, stop.message);
}

TEST(TransactionScoreboard, AHeldBeatMustNotMove) {
  History h(description());
  h.transaction(0x001);
  h.offer(0x001, 0);
  h.s.ready = false;
  h.edge();
  h.offer(0x002, 0);
  h.edge();
  EXPECT_EQ(h.sb.first_failure()->check, "stalled_output");
}

}  // namespace
}  // namespace aesim
