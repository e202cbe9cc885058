// The rung table: every fidelity has one rung, auto follows the capabilities, refusals name the
// rungs that can serve the request, and only the SystemC rungs set up a kernel.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/kernel/systemc_kernel.hpp"
#include "aesim/rungs/rung.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"

namespace aesim {
namespace {

using testing::exact_sensor;

std::string refusal(const SensorConfig& c, const SimulationRequest& request) {
  try {
    choose_rung(c, request);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RungTable, EveryFidelityHasExactlyOneRung) {
  std::set<Fidelity> seen;
  for (const Rung* rung : rung_table()) EXPECT_TRUE(seen.insert(rung->fidelity()).second) << to_string(rung->fidelity());
  for (Fidelity f : {Fidelity::Queue, Fidelity::Event, Fidelity::Cycle, Fidelity::PixelProcesses, Fidelity::FixedStep}) {
    EXPECT_EQ(rung_for(f).fidelity(), f);
  }
  EXPECT_EQ(seen.count(Fidelity::Auto), 0u);
}

TEST(RungTable, AutoTakesTheEventRungUnlessWiresOrAReceiverAreAsked) {
  SensorConfig c = exact_sensor(32, 32, 32);
  c.bus.access = BusAccess::Aloha;
  c.sim.fidelity = Fidelity::Auto;
  EXPECT_EQ(choose_rung(c, {}).fidelity(), Fidelity::Event);
  SimulationRequest waves;
  waves.waveforms = true;
  EXPECT_EQ(choose_rung(c, waves).fidelity(), Fidelity::Cycle);
  c.receiver.model = ReceiverModel::Rtl;
  EXPECT_EQ(choose_rung(c, {}).fidelity(), Fidelity::Cycle);
}

TEST(RungTable, RefusalsNameTheKeyAndTheRungsThatCanServe) {
  SensorConfig c = exact_sensor(32, 32, 32);
  SimulationRequest waves;
  waves.waveforms = true;
  c.sim.fidelity = Fidelity::Queue;
  EXPECT_EQ(refusal(c, waves), "--vcd dumps the clocked bus wires, which exist at sim.fidelity=cycle (or auto), not queue");
  c.sim.fidelity = Fidelity::Event;
  c.receiver.model = ReceiverModel::Rtl;
  EXPECT_EQ(refusal(c, {}), "receiver.model=rtl runs at sim.fidelity=cycle (or auto), not event");
  c.receiver.model = ReceiverModel::Reference;
  c.sim.fidelity = Fidelity::FixedStep;
  c.pixel.shot_noise = true;
  EXPECT_EQ(refusal(c, {}), "pixel.shot_noise is not modelled at sim.fidelity=fixed_step");
  c.pixel.shot_noise = false;
  c.sim.fidelity = Fidelity::Cycle;
  c.bus.access = BusAccess::Arbitrated;
  EXPECT_NE(refusal(c, {}).find("bus.access=arbitrated has no cycle-level model"), std::string::npos);
  // The same request through auto reaches the cycle rung's own check.
  c.sim.fidelity = Fidelity::Auto;
  EXPECT_NE(refusal(c, waves).find("bus.access=arbitrated"), std::string::npos);
}

TEST(RungTable, OnlyTheSystemCRungsSetUpAKernel) {
  SensorConfig c = exact_sensor(16, 16, 16);
  c.bus.access = BusAccess::Aloha;
  c.sim.duration = 0.05;
  c.pixel.i_max = 1e-10;  // 1 kHz at full scale: every rung fires within the run
  const Scene scene = testing::make_scene({testing::make_image(16, 16, [](int x, int y) { return (x + y) / 30.0; })});
  const Photocurrents photocurrents(scene, c.pixel);
  for (const Rung* rung : rung_table()) {
    c.sim.fidelity = rung->fidelity();
    const std::uint64_t before = ScopedKernel::made();
    const SimulationResult r = simulate(c.resolved(), photocurrents);
    EXPECT_GT(r.log.totals().fired, 0u) << to_string(rung->fidelity());
    const bool systemc = rung->fidelity() == Fidelity::Cycle || rung->fidelity() == Fidelity::PixelProcesses ||
                         rung->fidelity() == Fidelity::FixedStep;
    EXPECT_EQ(ScopedKernel::made() - before, systemc ? 1u : 0u) << to_string(rung->fidelity());
  }
}

}  // namespace
}  // namespace aesim
