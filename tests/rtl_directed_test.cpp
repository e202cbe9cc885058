// Directed tests of the Verilated receiver RTL. A bench drives its pins at falling edges from a
// per-cycle script and records, after every rising edge, what the RTL did. In every test the
// scoreboard also steps the reference model beside the RTL and must see no difference.
#include <functional>
#include <systemc>
#include <vector>

#include <gtest/gtest.h>

// The coverage run (scripts/coverage) compiles these same tests against the coverage builds.
#ifdef AESIM_RTL_COVERAGE
#include "Vaer_receiver_cov_drop.h"
#include "Vaer_receiver_cov_hold.h"
#include "Vaer_receiver_cov_ts8.h"
using Vaer_receiver_drop = Vaer_receiver_cov_drop;
using Vaer_receiver_hold = Vaer_receiver_cov_hold;
using Vaer_receiver_ts8 = Vaer_receiver_cov_ts8;
#include <cstdlib>
#include <string>
#include <verilated_cov.h>
#else
#include "Vaer_receiver_drop.h"
#include "Vaer_receiver_hold.h"
#include "Vaer_receiver_ts8.h"
#endif
#include "aesim/cosim/rtl_receiver.hpp"
#include "aesim/receiver/stream_monitor.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/kernel/systemc_kernel.hpp"

namespace aesim {
namespace {

struct Cycle {
  bool ack = false, valid = false, idle = false;
  std::uint32_t events = 0, collisions = 0, overflows = 0, fifo_count = 0;
};
struct Taken {
  std::uint64_t cycle;
  std::uint32_t ts, addr;
  bool flags;
};

template <class V>
class Bench : public sc_core::sc_module {
 public:
  using Script = std::function<void(ReceiverSignals&, std::uint64_t cycle)>;

  Bench(const ReceiverCycleModel::Config& config, Script script, std::uint64_t cycles)
      : sc_module(sc_core::sc_module_name("bench")), rx("rx", s, config), monitor("monitor", s), script_(std::move(script)), cycles_(cycles) {
    s.prescale.write(config.prescale);
    s.fifo_limit.write(config.fifo_limit);
    s.discard_collisions.write(config.discard_collisions);
    s.ts_external.write(config.ts_external);
    s.evt_ready.write(true);
    SC_THREAD(run);
  }
  SC_HAS_PROCESS(Bench);

  ReceiverSignals s;
  RtlReceiver<V> rx;
  StreamMonitor monitor;
  std::vector<Cycle> after;  // after[k]: outputs after rising edge k (k from 1)
  std::vector<Taken> taken;

 private:
  void run() {
    const sc_core::sc_time half(10, sc_core::SC_NS);
    s.rst_n.write(false);
    wait(half);
    s.rst_n.write(true);
    after.push_back({});
    for (std::uint64_t k = 1; k <= cycles_; ++k) {
      wait(half);  // falling edge k-1 .. rising edge k
      if (s.evt_valid.read() && s.evt_ready.read()) {
        taken.push_back({k, s.evt_ts.read(), s.evt_addr.read(), s.evt_flags.read()});
      }
      s.clk.write(true);
      wait(half);
      s.clk.write(false);
      after.push_back({s.ack.read(), s.evt_valid.read(), s.idle.read(), s.events.read(), s.collisions.read(),
                       s.overflows.read(), s.fifo_count.read()});
      script_(s, k);  // inputs for rising edge k+1
    }
  }
  Script script_;
  std::uint64_t cycles_;
};

ReceiverCycleModel::Config config(bool hold = false, int ts_width = 32) {
  ReceiverCycleModel::Config c;
  c.addr_width = 16;
  c.ts_width = ts_width;
  c.capacity = 64;
  c.hold_when_full = hold;
  c.prescale = 1;
  c.fifo_limit = 16;
  c.discard_collisions = true;
  c.ts_external = false;
  return c;
}

// A finished bench with the SystemC context it ran in (destroyed after the bench).
template <class V>
struct BenchRun {
  std::unique_ptr<ScopedKernel> kernel = std::make_unique<ScopedKernel>();
  std::unique_ptr<Bench<V>> bench;
  Bench<V>* operator->() const { return bench.get(); }
};

template <class V>
BenchRun<V> run(const ReceiverCycleModel::Config& c, typename Bench<V>::Script script, std::uint64_t cycles) {
  BenchRun<V> out;
  out.bench = std::make_unique<Bench<V>>(c, std::move(script), cycles);
  Bench<V>* bench = out.bench.get();
  sc_core::sc_start();
  EXPECT_EQ(bench->rx.scoreboard_mismatches(), 0u) << bench->rx.first_mismatch();
  EXPECT_EQ(bench->monitor.violations(), 0u);
#ifdef AESIM_RTL_COVERAGE
  // Verilator's coverage registry points into the live model: write its counts now, then forget
  // them before the next bench registers its own.
  static int runs = 0;
  const char* dir = std::getenv("AESIM_COVERAGE_DIR");
  VerilatedCovContext* cov = Verilated::threadContextp()->coveragep();
  cov->write((std::string(dir ? dir : ".") + "/coverage_" + std::to_string(runs++) + ".dat").c_str());
  cov->clear();
#endif
  return out;
}

// Req (with an address) high from cycle `from` to `to` (set at falling edges, inclusive).
void pulse(ReceiverSignals& s, std::uint64_t k, std::uint64_t from, std::uint64_t to, std::uint32_t addr,
           bool contention = false) {
  if (k == from) {
    s.req.write(true);
    s.addr.write(addr);
    s.contention.write(contention);
  }
  if (k == to) {
    s.req.write(false);
    s.addr.write(0);
    s.contention.write(false);
  }
}

TEST(RtlDirected, SingleEventIsLatchedOnTheFourthEdgeAndReleased) {
  // Req rises after edge 5: the synchronizer's three flops hold it after edges 6, 7 and 8; the
  // settled second and third agree before edge 9, where the receiver latches and raises Ack. The
  // sender drops Req after edge 9; Ack falls at edge 13.
  auto b = run<Vaer_receiver_drop>(
      config(), [](ReceiverSignals& s, std::uint64_t k) { pulse(s, k, 5, 9, 0x2A5); }, 20);
  for (std::uint64_t k = 1; k <= 20; ++k) EXPECT_EQ(b->after[k].ack, k >= 9 && k < 13) << "edge " << k;
  ASSERT_EQ(b->taken.size(), 1u);
  EXPECT_EQ(b->taken[0].addr, 0x2A5u);
  EXPECT_EQ(b->taken[0].ts, 9u);  // the ticks completed by the latch edge 9 (prescale 1)
  EXPECT_FALSE(b->taken[0].flags);
  EXPECT_EQ(b->taken[0].cycle, 10u);  // offered after edge 9, taken at edge 10
  EXPECT_EQ(b->after[20].events, 1u);
  EXPECT_TRUE(b->after[20].idle);
  EXPECT_FALSE(b->after[9].idle);
}

TEST(RtlDirected, BackToBackEventsKeepTheirOrder) {
  // A second sender raises Req as soon as the first handshake ends (Ack low after edge 13).
  auto b = run<Vaer_receiver_drop>(
      config(),
      [](ReceiverSignals& s, std::uint64_t k) {
        pulse(s, k, 5, 9, 0x001);
        pulse(s, k, 13, 17, 0x3FF);
      },
      30);
  ASSERT_EQ(b->taken.size(), 2u);
  EXPECT_EQ(b->taken[0].addr, 0x001u);
  EXPECT_EQ(b->taken[1].addr, 0x3FFu);
  EXPECT_EQ(b->taken[1].ts, 17u);
}

TEST(RtlDirected, ReqGlitchShorterThanTheSynchronizerIsIgnored) {
  // High for one cycle only: one edge sees it, the receiver never sees two agreeing samples.
  auto b = run<Vaer_receiver_drop>(
      config(), [](ReceiverSignals& s, std::uint64_t k) { pulse(s, k, 5, 6, 0x155); }, 20);
  for (std::uint64_t k = 1; k <= 20; ++k) EXPECT_FALSE(b->after[k].ack) << "edge " << k;
  EXPECT_TRUE(b->taken.empty());
  EXPECT_EQ(b->after[20].events, 0u);
  EXPECT_TRUE(b->after[20].idle);
}

TEST(RtlDirected, CollisionIsCountedAndDiscardedOrFlagged) {
  auto script = [](ReceiverSignals& s, std::uint64_t k) { pulse(s, k, 5, 9, 0x0F3, true); };
  auto discard = run<Vaer_receiver_drop>(config(), script, 20);
  EXPECT_TRUE(discard->taken.empty());
  EXPECT_EQ(discard->after[20].collisions, 1u);
  EXPECT_EQ(discard->after[20].events, 0u);
  EXPECT_TRUE(discard->after[10].ack);  // still acknowledged, so the senders release

  ReceiverCycleModel::Config keep = config();
  keep.discard_collisions = false;
  auto flag = run<Vaer_receiver_drop>(keep, script, 20);
  ASSERT_EQ(flag->taken.size(), 1u);
  EXPECT_TRUE(flag->taken[0].flags);
  EXPECT_EQ(flag->taken[0].addr, 0x0F3u);
  EXPECT_EQ(flag->after[20].collisions, 1u);
}

// Four senders wanting the bus at cycles 5, 15, 25, 35, each waiting for an idle bus (Req and
// Ack low) and releasing Req once it sees Ack; nobody reads the FIFO (of 2) until cycle 60.
typename Bench<Vaer_receiver_drop>::Script four_senders_late_reader() {
  return [next = 0u](ReceiverSignals& s, std::uint64_t k) mutable {
    if (s.ack.read() && s.req.read()) pulse(s, k, 0, k, 0);
    const bool bus_idle = !s.req.read() && !s.ack.read();
    if (next < 4 && k >= 5 + 10 * next && bus_idle) {
      pulse(s, k, k, 0, 0x100 + next);
      ++next;
    }
    s.evt_ready.write(k >= 60);
  };
}

TEST(RtlDirected, FullFifoDropsAndCountsWithTheDropPolicy) {
  ReceiverCycleModel::Config c = config();
  c.fifo_limit = 2;
  auto b = run<Vaer_receiver_drop>(c, four_senders_late_reader(), 80);
  EXPECT_EQ(b->after[59].fifo_count, 2u);
  EXPECT_EQ(b->after[80].events, 2u);
  EXPECT_EQ(b->after[80].overflows, 2u);
  ASSERT_EQ(b->taken.size(), 2u);
  EXPECT_EQ(b->taken[0].addr, 0x100u);
  EXPECT_EQ(b->taken[1].addr, 0x101u);
}

TEST(RtlDirected, FullFifoHoldsAckBackWithTheHoldPolicy) {
  ReceiverCycleModel::Config c = config(true);
  c.fifo_limit = 2;
  auto b = run<Vaer_receiver_hold>(c, four_senders_late_reader(), 120);
  EXPECT_EQ(b->after[80].overflows, 0u);
  // The third sender waits for Ack until the reader frees a word at cycle 60.
  EXPECT_FALSE(b->after[59].ack);
  EXPECT_EQ(b->after[120].events, 4u);
  ASSERT_EQ(b->taken.size(), 4u);
  for (std::uint32_t i = 0; i < 4; ++i) EXPECT_EQ(b->taken[i].addr, 0x100u + i);
}

TEST(RtlDirected, CollisionIntoAFullFifoIsDroppedAndCountedTwice) {
  // Flagged events are kept (no discard); the first fills a one-word FIFO nobody reads, the
  // second arrives flagged and finds it full: one overflow, and it still counts as a collision.
  ReceiverCycleModel::Config c = config();
  c.fifo_limit = 1;
  c.discard_collisions = false;
  auto b = run<Vaer_receiver_drop>(
      c,
      [](ReceiverSignals& s, std::uint64_t k) {
        pulse(s, k, 5, 9, 0x011);
        pulse(s, k, 15, 19, 0x033, true);
        s.evt_ready.write(false);
      },
      30);
  EXPECT_EQ(b->after[30].events, 1u);
  EXPECT_EQ(b->after[30].overflows, 1u);
  EXPECT_EQ(b->after[30].collisions, 1u);
  EXPECT_EQ(b->after[30].fifo_count, 1u);
  EXPECT_TRUE(b->taken.empty());
}

TEST(RtlDirected, ResetInTheMiddleOfAHandshakeStartsClean) {
  // Reset while Ack is high and the sender still holds Req: Ack drops at once, counters clear;
  // after reset the sender, still holding Req, is latched again.
  auto b = run<Vaer_receiver_drop>(
      config(),
      [](ReceiverSignals& s, std::uint64_t k) {
        if (k == 5) pulse(s, k, 5, 0, 0x0AA);
        if (k == 9) s.rst_n.write(false);
        if (k == 10) s.rst_n.write(true);
        if (k > 13 && s.ack.read() && s.req.read()) pulse(s, k, 0, k, 0);
      },
      30);
  EXPECT_TRUE(b->after[9].ack);
  EXPECT_FALSE(b->after[10].ack);
  EXPECT_EQ(b->after[10].events, 0u);
  EXPECT_EQ(b->after[30].events, 1u);  // counted once, after the reset
  EXPECT_TRUE(b->after[30].idle);
  ASSERT_EQ(b->taken.size(), 1u);
  EXPECT_EQ(b->taken[0].addr, 0x0AAu);
}

TEST(RtlDirected, TimestampWrapsModuloItsWidth) {
  // An 8-bit counter at one tick per cycle wraps every 256 cycles.
  auto b = run<Vaer_receiver_ts8>(
      config(false, 8),
      [](ReceiverSignals& s, std::uint64_t k) {
        pulse(s, k, 250, 254, 0x001);
        pulse(s, k, 262, 266, 0x002);
      },
      280);
  ASSERT_EQ(b->taken.size(), 2u);
  EXPECT_EQ(b->taken[0].ts, 254u);
  EXPECT_EQ(b->taken[1].ts, (266u) % 256u);
}

TEST(RtlDirected, PrescaledTimestampCountsTicksNotCycles) {
  ReceiverCycleModel::Config c = config();
  c.prescale = 5;
  auto b = run<Vaer_receiver_drop>(
      c, [](ReceiverSignals& s, std::uint64_t k) { pulse(s, k, 40, 44, 0x010); }, 60);
  ASSERT_EQ(b->taken.size(), 1u);
  EXPECT_EQ(b->taken[0].ts, 44u / 5u);  // latched at edge 44: floor(44 / 5) ticks completed
}

TEST(RtlDirected, LongBackPressureKeepsEveryBeatInOrder) {
  // Events every 12 cycles from 12 to 228 (19 of them); the reader is not ready at all for 150
  // cycles (12 events wait, under the 16-word limit) and then one cycle in nine, faster than
  // they come: nothing overflows, every beat waits stable (the stream monitor checks) and all 19
  // leave in order.
  auto b = run<Vaer_receiver_drop>(
      config(),
      [](ReceiverSignals& s, std::uint64_t k) {
        if (k % 12 == 0 && k < 240 && !s.req.read()) pulse(s, k, k, 0, static_cast<std::uint32_t>(k / 12));
        if (s.ack.read() && s.req.read()) pulse(s, k, 0, k, 0);
        s.evt_ready.write(k > 150 && k % 9 == 0);
      },
      600);
  EXPECT_EQ(b->after[150].fifo_count, 12u);
  EXPECT_EQ(b->after[600].overflows, 0u);
  EXPECT_EQ(b->after[600].events, 19u);
  ASSERT_EQ(b->taken.size(), 19u);
  for (std::size_t i = 1; i < b->taken.size(); ++i) EXPECT_LT(b->taken[i - 1].addr, b->taken[i].addr);
}

}  // namespace
}  // namespace aesim
