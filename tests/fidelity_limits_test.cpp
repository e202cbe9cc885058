// Each rung driven past the edge of its validity: the outcome must be a correct result or a
// clear diagnostic, never a silent wrong answer, NaN, hang or crash. And the exact rungs agree.
#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/array/queue_model.hpp"
#include "aesim/summary/summary.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

using testing::exact_sensor;
using testing::make_image;
using testing::make_scene;

SimulationResult run(SensorConfig c, Fidelity f, const Scene& scene) {
  c.sim.fidelity = f;
  const Photocurrents photocurrents(scene, c.pixel);
  return simulate(c.resolved(), photocurrents, testing::with_truth());
}

std::map<std::uint32_t, std::uint64_t> counts(const SimulationResult& r, int cols) {
  std::map<std::uint32_t, std::uint64_t> n;
  for (const TruthRecord& t : r.log.truth()) ++n[t.firing.y * static_cast<std::uint32_t>(cols) + t.firing.x];
  return n;
}

// Mismatch, random start, reset time, an ALOHA bus with collisions, 32x32 in four tiles.
SensorConfig busy_small_sensor() {
  SensorConfig c = exact_sensor(32, 32, 16);
  c.pixel.mismatch = 0.05;
  c.pixel.initial = InitialState::Random;
  c.pixel.t_reset = 1e-3;
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = 2e-4;
  c.sim.duration = 3.0;
  return c;
}

// The one process per pixel baseline and the scheduled event rung must agree bit for bit.
void expect_processes_agree(const SensorConfig& c, const Scene& scene) {
  const SimulationResult a = run(c, Fidelity::Event, scene);
  const SimulationResult b = run(c, Fidelity::PixelProcesses, scene);
  ASSERT_GT(a.log.totals().collided, 10u);
  ASSERT_EQ(a.log.truth().size(), b.log.truth().size());
  for (std::size_t i = 0; i < a.log.truth().size(); ++i) {
    ASSERT_EQ(a.log.truth()[i].firing.t, b.log.truth()[i].firing.t) << i;
    ASSERT_EQ(a.log.truth()[i].firing.x, b.log.truth()[i].firing.x) << i;
    ASSERT_EQ(a.log.truth()[i].firing.y, b.log.truth()[i].firing.y) << i;
    ASSERT_EQ(a.log.truth()[i].fate, b.log.truth()[i].fate) << i;
  }
  ASSERT_EQ(a.log.events().size(), b.log.events().size());
}

TEST(Rungs, PixelProcessesAndTheScheduleGiveTheSameEvents) {
  // Shot noise and a moving scene: the event rung's tiles go through their calendars.
  SensorConfig c = busy_small_sensor();
  c.pixel.shot_noise = true;
  std::vector<Image> frames;
  for (int k = 0; k < 8; ++k) {
    frames.push_back(make_image(32, 32, [k](int x, int y) { return std::abs(x - 4 * k) < 6 ? 1.0 : 0.05 * (y % 3); }));
  }
  expect_processes_agree(c, make_scene(frames, 0.1, true));
}

TEST(Rungs, PixelProcessesAndTheWindowsGiveTheSameEvents) {
  // A still scene without shot noise: the event rung makes each tile's firings a window at a time
  // (FiringWindow), not through its calendar (ties are tested against the calendar in
  // firing_schedule_test).
  expect_processes_agree(busy_small_sensor(), make_scene({make_image(32, 32, [](int x, int y) {
                                                return x < 4 ? 1.0 : 0.05 * (1 + (x + y) % 9);
                                              })}));
}

TEST(Rungs, TilesOnThreadsGiveTheSameEventsAsOneThread) {
  SensorConfig c = exact_sensor(64, 64, 16);
  c.pixel.mismatch = 0.03;
  c.pixel.initial = InitialState::Random;
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = 1e-4;
  c.sim.duration = 2.0;
  const Scene scene = make_scene({make_image(64, 64, [](int x, int y) { return ((x * 7 + y * 3) % 11) / 10.0; })});
  c.sim.threads = 1;
  const SimulationResult one = run(c, Fidelity::Event, scene);
  c.sim.threads = 0;  // all cores: 16 tiles in any interleaving
  const SimulationResult all = run(c, Fidelity::Event, scene);
  ASSERT_GT(one.log.totals().collided, 0u);
  ASSERT_EQ(one.log.events().size(), all.log.events().size());
  for (std::size_t i = 0; i < one.log.events().size(); ++i) {
    ASSERT_EQ(one.log.events()[i].t, all.log.events()[i].t) << i;
    ASSERT_EQ(one.log.events()[i].bus_address, all.log.events()[i].bus_address) << i;
    ASSERT_EQ(one.log.events()[i].tile, all.log.events()[i].tile) << i;
  }
}

TEST(FixedStep, CoarserThanTheIntegrationTimeKeepsCountsAndSaysSo) {
  // 100 pA fires every 1 ms; a 10 ms step crosses ten thresholds per step. Counts must still be
  // right (10 per step), and the run must report the steps it quantised.
  SensorConfig c = exact_sensor(4, 4, 4);
  c.pixel.i_max = 100e-12;
  c.sim.duration = 0.5;
  c.sim.step = 10e-3;
  const Scene scene = make_scene({make_image(4, 4, [](int x, int) { return x < 2 ? 1.0 : 0.37; })});
  const SimulationResult fixed = run(c, Fidelity::FixedStep, scene);
  const SimulationResult exact = run(c, Fidelity::Event, scene);
  EXPECT_GT(fixed.facts.multi_fire_steps, 0u);
  const auto n_fixed = counts(fixed, 4);
  const auto n_exact = counts(exact, 4);
  for (const auto& [pixel, n] : n_exact) {
    const double got = static_cast<double>(n_fixed.count(pixel) ? n_fixed.at(pixel) : 0);
    EXPECT_NEAR(got, static_cast<double>(n), 1.0) << "pixel " << pixel;
  }
  // Its times are the step's: every firing sits on the 10 ms grid.
  for (const TruthRecord& t : fixed.log.truth()) {
    EXPECT_NEAR(std::remainder(t.firing.t, 10e-3), 0.0, 1e-12);
  }
}

TEST(FixedStep, FineEnoughStepHasNoDiagnosticAndSmallErrors) {
  SensorConfig c = exact_sensor(4, 4, 4);
  c.sim.duration = 1.0;
  c.sim.step = 1e-4;
  const Scene scene = make_scene({make_image(4, 4, [](int x, int y) { return 0.2 + 0.05 * (x + 4 * y); })});
  const SimulationResult fixed = run(c, Fidelity::FixedStep, scene);
  const SimulationResult exact = run(c, Fidelity::Event, scene);
  EXPECT_EQ(fixed.facts.multi_fire_steps, 0u);
  // Per pixel: each firing lands on the first tick at or after its exact time, so the k-th
  // firings pair up at most one step late, and a firing in the run's last step may be stamped
  // past its end: counts differ by at most one.
  std::map<std::uint32_t, std::vector<double>> a, b;
  for (const TruthRecord& t : exact.log.truth()) a[t.firing.y * 4 + t.firing.x].push_back(t.firing.t);
  for (const TruthRecord& t : fixed.log.truth()) b[t.firing.y * 4 + t.firing.x].push_back(t.firing.t);
  ASSERT_EQ(a.size(), 16u);
  for (const auto& [pixel, times] : a) {
    const std::vector<double>& got = b[pixel];
    EXPECT_LE(std::abs(static_cast<double>(got.size()) - static_cast<double>(times.size())), 1.0) << pixel;
    for (std::size_t k = 0; k < std::min(got.size(), times.size()); ++k) {
      EXPECT_GE(got[k] - times[k], -1e-9) << pixel << " firing " << k;
      EXPECT_LT(got[k] - times[k], 1e-4 + 1e-9) << pixel << " firing " << k;
    }
  }
}

TEST(Queue, BlackFrameEntersNothing) {
  EXPECT_TRUE(queue_order(std::vector<double>(16, 0.0), 10.0, 1.0).empty());
}

TEST(Queue, SingleLitPixelEntersEveryIteration) {
  std::vector<double> v(9, 0.0);
  v[4] = 0.5;  // f_max = 10 Hz over 2 s: round(10 * 0.5 * 2) = 10 iterations
  const auto q = queue_order(v, 10.0, 2.0);
  EXPECT_EQ(q, std::vector<std::uint32_t>(10, 4u));
}

TEST(Queue, NonIntegerRatiosRoundAsEquationThreeSays) {
  // P = {1.0, 0.4, 0.6, 0.25}: round(P_max/P_i) = 1, round(2.5) = 3, round(1.67) = 2, 4.
  // N = round(10 * 1.0 * 1.0) = 10 iterations; pixel i enters when n mod divisor == 0, and within
  // an iteration in raster order. Eq. 1 would give 4, 6 and 2.5 firings; eq. 3 gives 3, 5, 2.
  const auto q = queue_order({1.0, 0.4, 0.6, 0.25}, 10.0, 1.0);
  std::map<std::uint32_t, int> n;
  for (std::uint32_t i : q) ++n[i];
  EXPECT_EQ(n[0], 10);
  EXPECT_EQ(n[1], 3);
  EXPECT_EQ(n[2], 5);
  EXPECT_EQ(n[3], 2);
  // Iteration 1: pixel 0 only; iteration 2: 0 and 2; iteration 3: 0 and 1; iteration 4: 0, 2, 3.
  const std::vector<std::uint32_t> first = {0, 0, 2, 0, 1, 0, 2, 3};
  EXPECT_EQ(std::vector<std::uint32_t>(q.begin(), q.begin() + 8), first);
}

TEST(Queue, FramesFasterThanThePixelsAreReportedNotSilentlyEmpty) {
  // 1 kHz frames at full scale: 10 Hz * 1 ms rounds to zero iterations per frame. The queue model
  // cannot fire; it must say so. The event rung integrates across frames: ~10 firings per second.
  SensorConfig c = exact_sensor(2, 2, 2);
  c.sim.duration = 1.0;
  const Scene scene = make_scene({make_image(2, 2, [](int, int) { return 1.0; }),
                                  make_image(2, 2, [](int, int) { return 1.0; })},
                                 1e-3, true);
  const SimulationResult q = run(c, Fidelity::Queue, scene);
  EXPECT_EQ(q.log.totals().fired, 0u);
  EXPECT_EQ(q.facts.empty_queue_frames, 1000u);
  const SimulationResult e = run(c, Fidelity::Event, scene);
  EXPECT_EQ(e.log.totals().fired, 4u * 10u);
}

TEST(Light, TooDimToFireWithinTheRunOrSystemCsRangeAtEveryRung) {
  // 1e-21 A needs 1e8 s per firing, beyond a 1e6 s run and SystemC's 1.8e7 s range: no event,
  // no overflow, no hang, at every rung that has time.
  SensorConfig c = exact_sensor(2, 2, 2);
  c.pixel.i_max = 1e-21;
  c.sim.duration = 1e6;
  c.sim.step = 1e3;
  const Scene scene = make_scene({make_image(2, 2, [](int, int) { return 1.0; })});
  for (Fidelity f : {Fidelity::Event, Fidelity::PixelProcesses, Fidelity::FixedStep, Fidelity::Queue}) {
    const SimulationResult r = run(c, f, scene);
    EXPECT_EQ(r.log.totals().fired, 0u) << to_string(f);
  }
  c.bus.access = BusAccess::Aloha;
  const SimulationResult cycle = run(c, Fidelity::Cycle, scene);
  EXPECT_EQ(cycle.log.totals().fired, 0u);
}

TEST(Bus, FarAboveSaturationThroughputGoesToZeroWithoutLivelock) {
  // 64x64 full-scale light: 10,240 events per bus per second. tau = 10 ms makes G ~ 100.
  SensorConfig c = exact_sensor(64, 64, 32);
  c.pixel.initial = InitialState::Random;
  c.pixel.mismatch = 0.02;
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = 10e-3;
  c.receiver.clock = 550;  // a 5.5-period handshake: ~10 ms
  c.receiver.tick = 1.0 / 550;
  c.sim.duration = 1.0;
  const Scene scene = make_scene({make_image(64, 64, [](int, int) { return 1.0; })});
  for (Fidelity f : {Fidelity::Event, Fidelity::Cycle}) {
    const SimulationResult r = run(c, f, scene);
    const nlohmann::json s = make_summary(c, r.log, r.facts);
    EXPECT_GT(s["offered_load"].get<double>(), 50) << to_string(f);
    EXPECT_LT(s["throughput"].get<double>(), 1e-3) << to_string(f);
    EXPECT_EQ(r.log.totals().fired, r.log.totals().delivered + r.log.totals().collided) << to_string(f);
  }
}

TEST(Bus, IdenticalSynchronisedPixelsAllCollideAtEveryTimedRung) {
  // Reset start, no mismatch, equal light: every pixel of a bus fires at the same instant.
  SensorConfig c = exact_sensor(16, 16, 8);
  c.bus.access = BusAccess::Aloha;
  c.sim.duration = 1.0;
  c.sim.step = 1e-4;
  const Scene scene = make_scene({make_image(16, 16, [](int, int) { return 1.0; })});
  for (Fidelity f : {Fidelity::Event, Fidelity::PixelProcesses, Fidelity::Cycle, Fidelity::FixedStep}) {
    const SimulationResult r = run(c, f, scene);
    EXPECT_GT(r.log.totals().fired, 0u) << to_string(f);
    EXPECT_EQ(r.log.totals().collided, r.log.totals().fired) << to_string(f);
  }
}

}  // namespace
}  // namespace aesim
