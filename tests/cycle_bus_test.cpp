// The cycle fidelity: a clocked wired-OR bus, Req/Ack and the reference receiver, on
// hand-computed timings, protocol invariants, and against the event fidelity at low load.
#include <algorithm>
#include <ostream>
#include <cmath>
#include <set>
#include <systemc>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/bus/pixel_bus_if.hpp"
#include "aesim/bus/clocked_aloha_bus.hpp"
#include "aesim/bus/handshake_rules.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/tile/cycle_tile.hpp"
#include "aesim/summary/summary.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/kernel/systemc_kernel.hpp"

namespace aesim {
namespace {

constexpr double kPeriod = 20e-9;  // 50 MHz receiver clock

// The timestamp a receiver gives an event it latched at time t_latch: the free-running counter
// holds floor((k - 1) / prescale) ticks before edge k = t_latch / period.
double stamp(double t_latch, double period, unsigned prescale) {
  const auto k = static_cast<std::uint64_t>(std::llround(t_latch / period));
  return static_cast<double>(k / prescale) * prescale * period;
}

// Fires chosen pixels at chosen times into a bus, as pixels would.
class Stimulus : public sc_core::sc_module {
 public:
  sc_core::sc_port<PixelBusIf> bus;
  Stimulus(const sc_core::sc_module_name& name, std::vector<AddressEvent> firings)
      : sc_module(name), firings_(std::move(firings)) {
    SC_THREAD(run);
  }
  SC_HAS_PROCESS(Stimulus);

 private:
  void run() {
    for (const AddressEvent& f : firings_) {
      wait(sc_core::sc_time(f.t, sc_core::SC_SEC) - sc_core::sc_time_stamp());
      bus->request(f);
    }
  }
  std::vector<AddressEvent> firings_;
};

struct CycleRun {
  EventLog log{1, true};
  double tau = 0;
  std::uint64_t violations = 0;
};

// Two pixels of a 32x32 tile: (1, 2) fires at 1 us (exactly on a clock edge), (4, 8) `delta` later.
CycleRun two_firings(double delta, bool detect) {
  const ScopedKernel kernel;
  SensorConfig c = testing::exact_sensor(32, 32, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.contention_detect = detect;
  const AddressMap map(c.array);
  CycleRun out;
  auto make = [&](double t, std::uint32_t x, std::uint32_t y) {
    AddressEvent e;
    e.t = t;
    e.x = x;
    e.y = y;
    e.bus_address = map.bus_address({x, y});
    return e;
  };
  CycleTile tile("tile0", 0, map, c, out.log, nullptr, CycleOptions{});
  PixelBusPort port("port", tile.bus());
  Stimulus stim("stim", {make(1e-6, 1, 2), make(1e-6 + delta, 4, 8)});
  stim.bus.bind(port);
  sc_core::sc_start();
  out.log.finish();
  out.tau = tile.stats().measured_tau;
  out.violations = tile.stats().protocol_violations;
  return out;
}

std::vector<Fate> fates(const EventLog& log) {
  std::vector<Fate> v;
  for (const TruthRecord& r : log.truth()) v.push_back(r.fate);
  return v;
}

// The firing falls exactly on an edge at t0, so it drives 1 ps later; the synchronizer's flops
// take it at t0 + 1, 2, 3 periods, the receiver latches and raises Ack at t0 + 4 periods (the
// settled second and third flops agree); Req falls at once, Ack falls 4 edges later at t0 + 8
// periods: a 160 ns transaction less that picosecond.
TEST(CycleBus, LoneEventIsLatchedOnTheFourthEdge) {
  const CycleRun r = two_firings(1e-3, true);  // the second firing is far away
  EXPECT_EQ(fates(r.log), (std::vector<Fate>{Fate::Delivered, Fate::Delivered}));
  ASSERT_EQ(r.log.events().size(), 2u);
  EXPECT_NEAR(r.log.truth()[0].t_deliver - r.log.truth()[0].firing.t, 4 * kPeriod, 1e-15);
  // Latched at edge 54 of the 50 MHz clock; 50 cycles per 1 us tick: timestamp 1 tick.
  EXPECT_NEAR(r.log.events()[0].t, 1e-6, 1e-15);
  EXPECT_NEAR(r.tau, 8 * kPeriod - 1e-12, 1e-15);
  EXPECT_EQ(r.violations, 0u);
}

TEST(CycleBus, SecondDriverBeforeTheLatchCorruptsBoth) {
  const CycleRun r = two_firings(1.5 * kPeriod, true);
  EXPECT_EQ(fates(r.log), (std::vector<Fate>{Fate::Collided, Fate::Collided}));
  EXPECT_TRUE(r.log.events().empty());  // flagged by the contention line and discarded
  EXPECT_EQ(r.log.totals().collided, 2u);
}

TEST(CycleBus, WithoutContentionDetectionTheOrIsOutputAsAGhost) {
  const CycleRun r = two_firings(1.5 * kPeriod, false);
  EXPECT_EQ(fates(r.log), (std::vector<Fate>{Fate::Ghost, Fate::Ghost}));
  ASSERT_EQ(r.log.events().size(), 1u);
  EXPECT_EQ(r.log.events()[0].bus_address, (10u << 5) | 5u);  // (1,2) | (4,8) = (5,10)
  EXPECT_EQ(r.log.events()[0].x, 5u);
  EXPECT_EQ(r.log.events()[0].y, 10u);
  EXPECT_EQ(r.log.events()[0].flags, kGhostEvent);
}

TEST(CycleBus, FiringWhileAckIsHighIsAbsorbed) {
  // 4.5 periods after the first: the receiver has latched (at 4) and Ack is high until 8.
  const CycleRun r = two_firings(4.5 * kPeriod, true);
  EXPECT_EQ(fates(r.log), (std::vector<Fate>{Fate::Delivered, Fate::Absorbed}));
  ASSERT_EQ(r.log.events().size(), 1u);
  EXPECT_EQ(r.log.events()[0].x, 1u);
  EXPECT_EQ(r.violations, 0u);
}

TEST(CycleBus, FiringAfterAckFallsStartsItsOwnTransaction) {
  const CycleRun r = two_firings(8.5 * kPeriod, true);
  EXPECT_EQ(fates(r.log), (std::vector<Fate>{Fate::Delivered, Fate::Delivered}));
  // The second Req rises between edges, so it waits 3.5 periods for its 4th edge.
  EXPECT_NEAR(r.log.truth()[1].t_deliver - r.log.truth()[1].firing.t, 3.5 * kPeriod, 1e-15);
}

TEST(HandshakeRules, CountsEachBrokenRuleOnce) {
  HandshakeRules rules;
  rules.req_changed(true, false);   // a transaction, by the rules
  rules.ack_changed(true, true);
  rules.req_changed(false, true);
  rules.ack_changed(false, false);
  EXPECT_EQ(rules.violations(), 0u);
  rules.ack_changed(true, false);   // Ack with no Req
  rules.req_changed(true, true);    // Req rising while Ack is high
  rules.ack_changed(false, true);   // Ack falling while Req is high
  rules.req_changed(false, false);  // Req dropped before any Ack
  EXPECT_EQ(rules.violations(), 4u);
}

TEST(CycleBus, CountsAnAckThatRisesWithNoReq) {
  // A broken receiver raises and drops Ack with no pixel requesting; then a pixel fires and gets
  // no answer. The bus sees every change of Ack and counts the one that broke the handshake, and
  // the firing it could not finish stays undecided.
  const ScopedKernel kernel;
  EventLog log(1, true);
  ReceiverSignals wires;
  ClockedAlohaBus bus("bus", wires, sc_core::sc_time(20, sc_core::SC_NS), true, log);
  struct Bad : sc_core::sc_module {
    sc_core::sc_signal<bool>& ack;
    EventBus& bus;
    Bad(const sc_core::sc_module_name& n, sc_core::sc_signal<bool>& a, EventBus& b) : sc_module(n), ack(a), bus(b) {
      SC_THREAD(run);
    }
    SC_HAS_PROCESS(Bad);
    void run() {
      wait(10, sc_core::SC_NS);
      ack.write(true);
      wait(10, sc_core::SC_NS);
      ack.write(false);
      wait(15, sc_core::SC_NS);
      AddressEvent firing;
      firing.t = sc_core::sc_time_stamp().to_seconds();
      bus.request(firing);
    }
  } bad("bad", wires.ack, bus);
  sc_core::sc_start();
  EXPECT_EQ(bus.handshake_violations(), 1u);
  EXPECT_TRUE(wires.req.read());
  EXPECT_EQ(bus.measured_tau(), 0.0);
}

SimulationResult run_scene(SensorConfig c, const Image& img) {
  const Photocurrents photocurrents(testing::make_scene({img}), c.pixel);
  return simulate(c.resolved(), photocurrents, testing::with_truth());
}

TEST(CycleFidelity, LoadedBusKeepsTheHandshakeAndDeliversOnlyFiredPixels) {
  // The letter-like load of the aloha preset, with a slow clock (1 MHz: tau ~7.5 us) so that the
  // offered load reaches ~0.1 and collisions are common.
  SensorConfig c = testing::exact_sensor(64, 64, 32);
  c.bus.access = BusAccess::Aloha;
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.clock = 1e6;
  c.pixel.initial = InitialState::Random;
  c.pixel.mismatch = 0.02;
  c.sim.duration = 1.0;
  const SimulationResult r = run_scene(c, testing::make_image(64, 64, [](int x, int y) { return (x + y) % 3 ? 1.0 : 0.0; }));
  EXPECT_EQ(r.facts.protocol_violations, 0u);
  const TileCounters t = r.log.totals();
  EXPECT_GT(t.collided, 100u);
  EXPECT_EQ(t.fired, t.delivered + t.collided);
  // 4 edges up and 4 down, the first of each 0 to 1 period after its change.
  EXPECT_GT(r.facts.tau_s, 7 * 1e-6);
  EXPECT_LT(r.facts.tau_s, 8 * 1e-6);
  // Every output event is a firing that the truth says was delivered, stamped with its latch
  // time (1 MHz clock, 1 us tick: one cycle per tick).
  std::set<std::tuple<double, std::uint32_t, std::uint32_t>> delivered;
  for (const TruthRecord& rec : r.log.truth()) {
    if (rec.fate == Fate::Delivered) delivered.insert({stamp(rec.t_deliver, 1e-6, 1), rec.firing.x, rec.firing.y});
  }
  ASSERT_EQ(delivered.size(), r.log.events().size());
  for (const AddressEvent& e : r.log.events()) {
    ASSERT_TRUE(delivered.count({e.t, e.x, e.y})) << e.x << "," << e.y << " at " << e.t;
    ASSERT_TRUE((e.x + e.y) % 3 != 0) << "a dark pixel was delivered";
  }
}

TEST(CycleFidelity, AtLowLoadDeliversExactlyWhatTheEventFidelityDelivers) {
  SensorConfig c = testing::exact_sensor(64, 64, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = 110e-9;
  c.pixel.initial = InitialState::Random;
  c.pixel.mismatch = 0.02;
  c.sim.duration = 1.0;
  const Image img = testing::make_image(64, 64, [](int x, int y) { return (7 * x + 13 * y) % 29 == 0 ? 1.0 : 0.0; });
  c.sim.fidelity = Fidelity::Event;
  const SimulationResult ev = run_scene(c, img);
  c.sim.fidelity = Fidelity::Cycle;
  const SimulationResult cy = run_scene(c, img);

  // Precondition on the stimulus: G < 0.01 and no two firings on one bus within 20 clock
  // periods, so neither model has a collision to judge differently.
  const auto s = make_summary(c, cy.log, cy.facts);
  ASSERT_LT(s["offered_load"].get<double>(), 0.01);
  std::vector<std::vector<double>> per_tile(4);
  for (const TruthRecord& t : ev.log.truth()) per_tile[t.firing.tile].push_back(t.firing.t);
  for (auto& times : per_tile) {
    std::sort(times.begin(), times.end());
    for (std::size_t i = 1; i < times.size(); ++i) ASSERT_GT(times[i] - times[i - 1], 20 * kPeriod);
  }

  ASSERT_GT(ev.log.events().size(), 500u);
  ASSERT_EQ(ev.log.events().size(), cy.log.events().size());
  EXPECT_EQ(ev.log.totals().collided, 0u);
  EXPECT_EQ(cy.log.totals().collided, 0u);
  std::vector<TruthRecord> latched;
  for (const TruthRecord& t : cy.log.truth()) {
    if (t.fate == Fate::Delivered) latched.push_back(t);
  }
  std::sort(latched.begin(), latched.end(),
            [](const TruthRecord& a, const TruthRecord& b) { return a.t_deliver < b.t_deliver; });
  ASSERT_EQ(latched.size(), ev.log.events().size());
  for (std::size_t i = 0; i < ev.log.events().size(); ++i) {
    const AddressEvent& a = ev.log.events()[i];
    const AddressEvent& b = cy.log.events()[i];
    ASSERT_EQ(a.x, b.x) << i;
    ASSERT_EQ(a.y, b.y) << i;
    ASSERT_EQ(latched[i].firing.x, a.x) << i;
    ASSERT_EQ(latched[i].firing.t, a.t) << i;  // the same firing
    // The receiver latches on the 4th clock edge after Req: 3 to 4 periods after the firing, and
    // stamps it from its counter.
    const double delay = latched[i].t_deliver - a.t;
    ASSERT_GE(delay, 3 * kPeriod - 1e-12) << i;
    ASSERT_LE(delay, 4 * kPeriod + 1e-12) << i;
    ASSERT_NEAR(b.t, stamp(latched[i].t_deliver, kPeriod, 50), 1e-12) << i;
  }
}

}  // namespace
}  // namespace aesim

namespace aesim {
namespace {

// The reference receiver runs as one process per clock edge (ReferenceClockDomain); as a module
// on a clock wire with the sink and stream monitor beside it (what a Verilated receiver gets), it
// must give the same run: every output event, every fate and delivery time, every clock edge.
struct DomainCase {
  const char* name;
  const char* scene;
  double clock_hz;
  FullPolicy policy;
  int fifo_depth;
  unsigned ready_every;  // the consumer is ready one cycle in this many
  bool contention_detect;
  bool free_running;
};

void PrintTo(const DomainCase& c, std::ostream* os) { *os << c.name; }

class ClockDomain : public ::testing::TestWithParam<DomainCase> {};

TEST_P(ClockDomain, OneProcessPerEdgeEqualsTheReceiverOnAClockWire) {
  const DomainCase& k = GetParam();
  SensorConfig c = load_sensor("aloha");
  c.sim.fidelity = Fidelity::Cycle;
  c.sim.duration = k.free_running ? 0.05 : 0.5;
  c.receiver.clock = k.clock_hz;
  c.receiver.full_policy = k.policy;
  c.receiver.fifo_depth = k.fifo_depth;
  c.bus.contention_detect = k.contention_detect;
  const Photocurrents photocurrents(
      load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/" + k.scene), c.array, c.scene), c.pixel);
  SimulationRequest request = testing::with_truth();
  const unsigned every = k.ready_every;
  if (every > 1) request.cycle.sink_ready = [every](std::uint64_t cycle) { return cycle % every == 0; };
  request.cycle.free_running_clock = k.free_running;
  const SimulationResult domain = simulate(c.resolved(), photocurrents, request);
  request.cycle.receiver = reference_receiver_factory();
  const SimulationResult wired = simulate(c.resolved(), photocurrents, request);

  EXPECT_EQ(domain.facts.receiver_clock_edges, wired.facts.receiver_clock_edges);
  EXPECT_EQ(domain.facts.protocol_violations, 0u);
  EXPECT_EQ(wired.facts.protocol_violations, 0u);
  EXPECT_EQ(domain.facts.tau_s, wired.facts.tau_s);
  ASSERT_GT(domain.log.events().size(), 100u);
  ASSERT_EQ(domain.log.events().size(), wired.log.events().size());
  for (std::size_t i = 0; i < domain.log.events().size(); ++i) {
    const AddressEvent& a = domain.log.events()[i];
    const AddressEvent& b = wired.log.events()[i];
    ASSERT_TRUE(a.t == b.t && a.bus_address == b.bus_address && a.tile == b.tile && a.flags == b.flags) << i;
  }
  ASSERT_EQ(domain.log.truth().size(), wired.log.truth().size());
  for (std::size_t i = 0; i < domain.log.truth().size(); ++i) {
    ASSERT_EQ(domain.log.truth()[i].fate, wired.log.truth()[i].fate) << i;
    ASSERT_EQ(domain.log.truth()[i].t_deliver, wired.log.truth()[i].t_deliver) << i;
  }
  const TileCounters t = domain.log.totals();
  if (every > 1 && k.policy == FullPolicy::Drop) {
    EXPECT_GT(t.dropped, 100u) << "the FIFO really filled";
  }
  if (!k.contention_detect) {
    EXPECT_GT(t.ghost, 10u) << "collisions went undetected";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Receivers, ClockDomain,
    ::testing::Values(DomainCase{"letter", "letters/A.pgm", 50e6, FullPolicy::Drop, 16, 1, true, false},
                      DomainCase{"slow_consumer_drops", "natural.pgm", 1e6, FullPolicy::Drop, 2, 400, true, false},
                      DomainCase{"slow_consumer_holds", "natural.pgm", 1e6, FullPolicy::Hold, 1, 400, true, false},
                      DomainCase{"ghosts", "checkerboard.pgm", 1e6, FullPolicy::Drop, 16, 1, false, false},
                      DomainCase{"free_running", "gradient.pgm", 5e6, FullPolicy::Hold, 4, 3, true, true}),
    [](const ::testing::TestParamInfo<DomainCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace aesim
