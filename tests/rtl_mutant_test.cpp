// The verification can fail: each deliberately broken RTL (scripts/rtl_mutants.py) runs the
// co-simulation of a scene, and the scoreboard must report mismatches; the real RTL, none.
// The run fills the FIFO to its full 64 words (a consumer ready one cycle in 400 at 1 MHz): a
// FIFO whose pointers skip a slot is indistinguishable from a good one until it is that full.
#include <gtest/gtest.h>

#include "Vaer_receiver_drop.h"
#include "Vmutant_ack_early.h"
#include "Vmutant_fifo_off_by_one.h"
#include "Vmutant_no_sync.h"
#include "aesim/cosim/rtl_receiver.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

template <class V>
std::uint64_t mismatches() {
  SensorConfig c = load_sensor("aloha");
  c.sim.fidelity = Fidelity::Cycle;
  c.sim.duration = 1.0;
  c.receiver.clock = 1e6;
  c.receiver.fifo_depth = 64;
  const Scene scene = load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/natural.pgm"), c.array, c.scene);
  const Photocurrents photocurrents(scene, c.pixel);
  SimulationRequest request;
  request.cycle.sink_ready = [](std::uint64_t cycle) { return cycle % 400 == 0; };
  request.cycle.receiver = [](const std::string& name, std::uint32_t, ReceiverSignals& s,
                              const ReceiverCycleModel::Config& config) {
    return std::unique_ptr<ReceiverModule>(new RtlReceiver<V>(name.c_str(), s, config));
  };
  const SimulationResult r = simulate(c.resolved(), photocurrents, request);
  EXPECT_GT(r.facts.scoreboard_beats, 1000u);
  return r.facts.scoreboard_mismatches;
}

TEST(RtlMutants, TheRealRtlPasses) { EXPECT_EQ(mismatches<Vaer_receiver_drop>(), 0u); }
TEST(RtlMutants, MissingSynchronizerIsCaught) { EXPECT_GT(mismatches<Vmutant_no_sync>(), 0u); }
TEST(RtlMutants, AckOneCycleEarlyIsCaught) { EXPECT_GT(mismatches<Vmutant_ack_early>(), 0u); }
TEST(RtlMutants, FifoPointerOffByOneIsCaught) { EXPECT_GT(mismatches<Vmutant_fifo_off_by_one>(), 0u); }

}  // namespace
}  // namespace aesim
