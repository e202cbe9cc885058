// The event fidelity against pure ALOHA theory, and where the theory fails (lock-step pixels).
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/summary/summary.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

// 64x64 uniform full-scale light in four 32x32 tiles: 1024 pixels per bus at 10 Hz, so tau
// sets the offered load G = 10240 /s * tau.
SensorConfig uniform_aloha(double load) {
  SensorConfig c = testing::exact_sensor(64, 64, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = load / 10240.0;
  c.sim.duration = 2.0;
  c.sim.seed = 11;
  return c;
}

nlohmann::json run(const SensorConfig& c) {
  const Photocurrents photocurrents(testing::make_scene({testing::make_image(64, 64, [](int, int) { return 1.0; })}),
                                    c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  return make_summary(c, r.log, r.facts);
}

class PureAlohaTheory : public ::testing::TestWithParam<double> {};

TEST_P(PureAlohaTheory, RandomPhasesAndMismatchMatchGExpMinus2G) {
  SensorConfig c = uniform_aloha(GetParam());
  c.pixel.initial = InitialState::Random;
  c.pixel.mismatch = 0.02;
  const nlohmann::json s = run(c);
  const double g = s["offered_load"];
  const double n = s["events_fired"];
  const double lost = s["collision_fraction"];
  EXPECT_NEAR(g, GetParam(), 0.01 * GetParam());  // 2 % mismatch barely moves the mean rate
  // Each period (0.1 s) the 1024 phases of a bus are uniform and, with 2 % mismatch, drift by
  // ~2.8 ms between periods, far more than tau: periods are independent samples. Events lost
  // together come in clusters of mean size ~1 + 2G, so the binomial standard error is inflated
  // by that factor's square root. Bound: four such standard errors.
  const double p = 1 - std::exp(-2 * g);
  const double se = std::sqrt(p * (1 - p) / n * (1 + 2 * g));
  EXPECT_NEAR(lost, p, 4 * se) << "G = " << g;
  const double s_theory = g * std::exp(-2 * g);
  EXPECT_NEAR(s["throughput"].get<double>(), s_theory, 4 * g * se) << "G = " << g;
}

INSTANTIATE_TEST_SUITE_P(Loads, PureAlohaTheory, ::testing::Values(0.1, 0.5, 1.0));

TEST(ArbitratedBus, MeanWaitIsTheMD1QueueWait) {
  // Random phases make each bus's arrivals near-Poisson and the service time is tau, so the mean
  // wait is M/D/1's G tau / (2 (1 - G)): 0.5 tau at G = 0.5. Over 4 s (160 k events) the mean
  // wait scatters by ~1.2 % from seed to seed; the bound is four of those.
  SensorConfig c = uniform_aloha(0.5);
  c.bus.access = BusAccess::Arbitrated;
  c.pixel.initial = InitialState::Random;
  c.pixel.mismatch = 0.02;
  c.sim.duration = 4.0;
  const nlohmann::json s = run(c);
  const double g = s["offered_load"];
  const double wait = s["latency_mean_s"].get<double>() / s["tau_s"].get<double>();
  EXPECT_NEAR(wait, g / (2 * (1 - g)), 0.05 * g / (2 * (1 - g)));
  // Nothing is lost; an event fired in the last moments may still be queued at the end.
  EXPECT_EQ(s["events_collided"], 0);
  EXPECT_LE(s["events_pending"].get<double>(), 10);
  EXPECT_EQ(s["events_delivered"].get<double>() + s["events_pending"].get<double>(), s["events_fired"].get<double>());
}

TEST(PureAlohaTheoryFails, LockStepPixelsCollideEveryTime) {
  // Reset start, no mismatch: all 1024 equally lit pixels of a bus fire at the same instant,
  // every period. Theory predicts 18 % loss at G = 0.1; the bus loses everything.
  const nlohmann::json s = run(uniform_aloha(0.1));
  EXPECT_EQ(s["events_collided"], s["events_fired"]);
  EXPECT_EQ(s["events_delivered"], 0);
  EXPECT_EQ(s["throughput"], 0.0);
}

TEST(PureAlohaTheoryFails, MismatchAloneBreaksTheLockStepOverTime) {
  // Reset start with 2 % mismatch: the k-th firings of a bus spread only over ~k * 2 ms, so the
  // first periods collide far above theory; as pixels drift apart the loss falls toward it.
  SensorConfig c = uniform_aloha(0.1);
  c.pixel.mismatch = 0.02;
  const Photocurrents photocurrents(testing::make_scene({testing::make_image(64, 64, [](int, int) { return 1.0; })}),
                                    c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents, testing::with_truth());
  double first_lost = 0, first = 0, last_lost = 0, last = 0;
  for (const TruthRecord& t : r.log.truth()) {
    const bool lost = t.fate != Fate::Delivered;
    if (t.firing.t < 0.15) {
      first += 1;
      first_lost += lost;
    } else if (t.firing.t > 1.6) {
      last += 1;
      last_lost += lost;
    }
  }
  const double theory = 1 - std::exp(-0.2);
  EXPECT_GT(first_lost / first, 3 * theory);
  EXPECT_LT(last_lost / last, first_lost / first);
}

}  // namespace
}  // namespace aesim
