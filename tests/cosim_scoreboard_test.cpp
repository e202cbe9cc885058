// Co-simulation: scene runs drive the Verilated receiver RTL through the cycle-level bus; at
// every clock edge the scoreboard steps the reference model with the same inputs and compares
// every output. The same runs with the reference receiver must give the same events.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/cosim/rtl_receiver.hpp"
#include "aesim/cosim/stepped_rtl_receiver.hpp"
#include "aesim/summary/summary.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/sanitized_build.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

struct CosimCase {
  const char* name;
  double clock_hz;  // sets tau and so the load
  std::uint64_t seed;
  FullPolicy policy;
  int fifo_depth;
  unsigned ready_every;  // the consumer is ready one cycle in this many (1: always)
  double duration;
};

void PrintTo(const CosimCase& c, std::ostream* os) { *os << c.name; }

class Cosim : public ::testing::TestWithParam<CosimCase> {};

TEST_P(Cosim, RtlMatchesTheReferenceEveryCycle) {
  const CosimCase& k = GetParam();
  SensorConfig c = load_sensor("aloha");
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.clock = k.clock_hz;
  c.receiver.full_policy = k.policy;
  c.receiver.fifo_depth = k.fifo_depth;
  c.sim.seed = k.seed;
  // scripts/test --full lengthens every run (AESIM_COSIM_SCALE) to compare millions of beats.
  const char* scale = std::getenv("AESIM_COSIM_SCALE");
  c.sim.duration = k.duration * (scale ? std::max(1.0, std::atof(scale)) : 1.0);
  const Scene scene = load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/natural.pgm"), c.array, c.scene);
  const Photocurrents photocurrents(scene, c.pixel);
  SimulationRequest request;
  const unsigned every = k.ready_every;
  request.cycle.sink_ready = [every](std::uint64_t cycle) { return cycle % every == 0; };

  c.receiver.model = ReceiverModel::Rtl;
  const SimulationResult rtl = simulate(c.resolved(), photocurrents, request);
  c.receiver.model = ReceiverModel::Reference;
  const SimulationResult ref = simulate(c.resolved(), photocurrents, request);

  EXPECT_EQ(rtl.facts.scoreboard_mismatches, 0u);
  EXPECT_EQ(rtl.facts.protocol_violations, 0u);
  EXPECT_EQ(ref.facts.protocol_violations, 0u);
  EXPECT_EQ(rtl.facts.scoreboard_beats, rtl.log.totals().delivered);
  EXPECT_GT(rtl.facts.scoreboard_beats, 10000u);
  ASSERT_EQ(rtl.log.events().size(), ref.log.events().size());
  for (std::size_t i = 0; i < rtl.log.events().size(); ++i) {
    const AddressEvent& a = rtl.log.events()[i];
    const AddressEvent& b = ref.log.events()[i];
    ASSERT_TRUE(a.t == b.t && a.bus_address == b.bus_address && a.tile == b.tile && a.flags == b.flags) << i;
  }
  const TileCounters r = rtl.log.totals();
  EXPECT_EQ(r.fired, r.delivered + r.collided + r.dropped);
  if (every > 1 && k.policy == FullPolicy::Drop) {
    EXPECT_GT(r.dropped, 1000u);  // the FIFO really filled
  }
  if (k.policy == FullPolicy::Hold) {
    EXPECT_EQ(r.dropped, 0u);
  }
  std::printf("[ cosim    ] %s: %llu beats compared, G = %.3f, %llu collided, %llu dropped\n", k.name,
              static_cast<unsigned long long>(rtl.facts.scoreboard_beats),
              make_summary(c, rtl.log, rtl.facts)["offered_load"].get<double>(),
              static_cast<unsigned long long>(r.collided), static_cast<unsigned long long>(r.dropped));
}

// Loads from light to heavy, two seeds, both FIFO policies, and back-pressure: a consumer ready
// one cycle in 400 (2,500 words/s at 1 MHz) against ~6,000 events/s per tile fills a 2-word FIFO,
// which then drops or holds the bus.
INSTANTIATE_TEST_SUITE_P(
    Loads, Cosim,
    ::testing::Values(CosimCase{"light", 2e6, 1, FullPolicy::Drop, 16, 1, 10.0},
                      CosimCase{"light_seed2", 2e6, 2, FullPolicy::Drop, 16, 1, 10.0},
                      CosimCase{"medium", 200e3, 3, FullPolicy::Drop, 16, 1, 8.0},
                      CosimCase{"heavy", 20e3, 4, FullPolicy::Drop, 16, 1, 8.0},
                      CosimCase{"backpressure_drop", 1e6, 5, FullPolicy::Drop, 2, 400, 2.0},
                      CosimCase{"backpressure_hold", 1e6, 6, FullPolicy::Hold, 2, 400, 2.0}),
    [](const ::testing::TestParamInfo<CosimCase>& info) { return std::string(info.param.name); });

TEST(ClockGating, StoppingTheIdleClockChangesNothing) {
  // The same run with the receiver clock running throughout and the RTL counting its own
  // timestamps, and with the clock stopped whenever the bus is idle and the timestamp fed from
  // the free-running count: same events, same timestamps, same fates, far fewer edges.
  SensorConfig c = load_sensor("aloha");
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.model = ReceiverModel::Rtl;
  c.receiver.clock = 100e3;  // slow, so the free-running run stays short
  c.sim.duration = 1.0;
  const Scene scene = load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/natural.pgm"), c.array, c.scene);
  const Photocurrents photocurrents(scene, c.pixel);
  SimulationRequest free_running = testing::with_truth();
  free_running.cycle.free_running_clock = true;
  const SimulationResult a = simulate(c.resolved(), photocurrents, free_running);
  const SimulationResult b = simulate(c.resolved(), photocurrents, testing::with_truth());
  EXPECT_EQ(a.facts.scoreboard_mismatches, 0u);
  EXPECT_EQ(b.facts.scoreboard_mismatches, 0u);
  ASSERT_GT(a.log.events().size(), 10000u);
  ASSERT_EQ(a.log.events().size(), b.log.events().size());
  for (std::size_t i = 0; i < a.log.events().size(); ++i) {
    ASSERT_EQ(a.log.events()[i].t, b.log.events()[i].t) << i;
    ASSERT_EQ(a.log.events()[i].bus_address, b.log.events()[i].bus_address) << i;
    ASSERT_EQ(a.log.events()[i].tile, b.log.events()[i].tile) << i;
  }
  ASSERT_EQ(a.log.truth().size(), b.log.truth().size());
  for (std::size_t i = 0; i < a.log.truth().size(); ++i) {
    ASSERT_EQ(a.log.truth()[i].fate, b.log.truth()[i].fate) << i;
    ASSERT_EQ(a.log.truth()[i].t_deliver, b.log.truth()[i].t_deliver) << i;
  }
  EXPECT_GE(a.facts.receiver_clock_edges, 4u * 100000u);  // 1 s at 100 kHz on each of 4 tiles
  EXPECT_LT(b.facts.receiver_clock_edges, a.facts.receiver_clock_edges / 2);
}

// The RTL as a plain C++ model stepped by the tile's clock domain (what receiver.model=rtl runs
// when no RTL trace is asked for) and the RTL as a SystemC model on a clock wire (what it runs
// with one): the same events, fates and stamps, and the same beats compared, under back-pressure.
// The natural scene at the cycle fidelity under back-pressure: a 1 MHz receiver with a 2-word
// FIFO and a consumer ready one cycle in 400, for `duration` s.
SensorConfig backpressured(double duration) {
  SensorConfig c = load_sensor("aloha");
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.clock = 1e6;
  c.receiver.fifo_depth = 2;
  c.sim.duration = duration;
  return c;
}
bool ready_one_in_400(std::uint64_t cycle) { return cycle % 400 == 0; }
Photocurrents natural_scene(const SensorConfig& c) {
  return Photocurrents(load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/natural.pgm"), c.array, c.scene),
                       c.pixel);
}

TEST(SteppedRtl, GivesTheClockWiresEventsAndBeats) {
  // Half a second under the sanitizers (the 2 s took 19 s there, 3.7 s in Release): the same code
  // runs, still past the beats and drops asked for below.
  SensorConfig c = backpressured(testing::kUnderAddressSanitizer ? 0.5 : 2.0);
  c.receiver.model = ReceiverModel::Rtl;
  const Photocurrents photocurrents = natural_scene(c);
  SimulationRequest stepped = testing::with_truth();
  stepped.cycle.sink_ready = ready_one_in_400;
  SimulationRequest wired = stepped;
  wired.cycle.receiver = rtl_receiver_factory(FullPolicy::Drop);
  const SimulationResult a = simulate(c.resolved(), photocurrents, stepped);
  const SimulationResult b = simulate(c.resolved(), photocurrents, wired);
  EXPECT_EQ(a.facts.scoreboard_mismatches, 0u);
  EXPECT_EQ(b.facts.scoreboard_mismatches, 0u);
  EXPECT_GT(a.facts.scoreboard_beats, 1000u);
  EXPECT_EQ(a.facts.scoreboard_beats, b.facts.scoreboard_beats);
  EXPECT_GT(a.log.totals().dropped, 100u);  // the 2-word FIFO filled
  ASSERT_EQ(a.log.events().size(), b.log.events().size());
  for (std::size_t i = 0; i < a.log.events().size(); ++i) {
    ASSERT_EQ(a.log.events()[i].t, b.log.events()[i].t) << i;
    ASSERT_EQ(a.log.events()[i].bus_address, b.log.events()[i].bus_address) << i;
    ASSERT_EQ(a.log.events()[i].tile, b.log.events()[i].tile) << i;
  }
  ASSERT_EQ(a.log.truth().size(), b.log.truth().size());
  for (std::size_t i = 0; i < a.log.truth().size(); ++i) ASSERT_EQ(a.log.truth()[i].fate, b.log.truth()[i].fate) << i;
}

// The stepped scoreboard can fail: the RTL built to hold the bus when its FIFO is full, checked
// against a reference that drops, under back-pressure, disagrees.
TEST(SteppedRtl, ItsScoreboardCatchesAReceiverThatDiffers) {
  const SensorConfig c = backpressured(1.0);
  const Photocurrents photocurrents = natural_scene(c);
  SimulationRequest request;
  request.cycle.sink_ready = ready_one_in_400;
  request.cycle.stepped_receiver = [](std::uint32_t, const ReceiverCycleModel::Config& config) {
    return make_stepped_rtl_receiver(FullPolicy::Hold, config);  // the reference drops
  };
  const SimulationResult r = simulate(c.resolved(), photocurrents, request);
  EXPECT_GT(r.facts.scoreboard_beats, 100u);
  EXPECT_GT(r.facts.scoreboard_mismatches, 0u);
}

}  // namespace
}  // namespace aesim
