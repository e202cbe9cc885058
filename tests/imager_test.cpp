// The Imager module in a caller's own SystemC context, as a user's sc_main holds it: its events
// equal simulate()'s at the cycle fidelity, event for event (each test is a process of its own,
// so each gets the one elaboration and sc_start() SystemC allows a context).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <systemc>

#include "embed/event_source.hpp"
#include "embed/imager.hpp"
#include "errors/input_error.hpp"
#include "run/imager_simulation.hpp"
#include "scene/photocurrents.hpp"

namespace aesim {
namespace {

const std::string kScene = std::string(AESIM_SOURCE_DIR) + "/scenes/hdr/window.pfm";

// simulate() on the aloha preset, the spec's scene and settings, at `fidelity`.
SimulationResult reference_run(const ImagerSpec& spec, const char* fidelity) {
  std::vector<Setting> settings = spec.settings;
  settings.push_back({"sim.fidelity", fidelity});
  const SceneFiles scene = find_scene(spec.scene);
  const ResolvedConfig config = configure_run(load_sensor("aloha"), scene, settings);
  const Photocurrents photocurrents(load_scene(scene, config.array, config.scene, config.sim.duration), config.pixel);
  return simulate(config, photocurrents);
}

TEST(Imager, RunsInTheCallersKernelWithTheCycleRungsEvents) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = {{"sim.duration", "300ms"}, {"bus.t_event", "2us"}, {"receiver.clock", "5MHz"}};

  // The reference: simulate() at the cycle fidelity, in a context of its own.
  const SimulationResult reference = reference_run(spec, "cycle");
  ASSERT_GT(reference.log.events().size(), 1000u);

  // The same in the default context, started by the caller as an sc_main would.
  Imager imager("imager", spec);
  sc_core::sc_start();
  EXPECT_EQ(sc_core::sc_get_status(), sc_core::SC_PAUSED);
  // The kernel starved after the last handshake before sim.duration: nothing runs past it.
  EXPECT_GT(sc_core::sc_time_stamp().to_seconds(), 0.29);
  EXPECT_LE(sc_core::sc_time_stamp().to_seconds(), 0.3);
  const std::vector<AddressEvent>& events = imager.events();
  ASSERT_EQ(events.size(), reference.log.events().size());
  std::size_t collided = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const AddressEvent& a = events[i];
    const AddressEvent& b = reference.log.events()[i];
    ASSERT_TRUE(a.t == b.t && a.x == b.x && a.y == b.y && a.tile == b.tile && a.flags == b.flags) << "event " << i;
  }
  for (const TileCounters& t : imager.tiles()) collided += t.collided;
  std::size_t reference_collided = 0;
  for (const TileCounters& t : reference.log.tiles()) reference_collided += t.collided;
  EXPECT_EQ(collided, reference_collided);
  EXPECT_GT(collided, 0u);  // 2 us transactions on the HDR scene: the bus is loaded
  EXPECT_DOUBLE_EQ(imager.tick(), 1e-6);
}

TEST(Imager, RefusesAnotherFidelityAndBadKeysBeforeElaborating) {
  ImagerSpec spec;
  spec.settings = {{"sim.fidelity", "event"}};
  EXPECT_THROW(Imager("a", spec), InputError);
  spec.settings = {{"pixel.cint", "1fF"}};
  EXPECT_THROW(Imager("b", spec), InputError);
  spec.settings = {};
  spec.scene = "no/such/scene.pgm";
  EXPECT_THROW(Imager("c", spec), InputError);
}

// A consumer of the caller's own reads the event fidelity's events from an sc_fifo: every event of
// simulate()'s event rung, in order, each read at its delivery time (to the 1 ps step).
struct Consumer : sc_core::sc_module {
  sc_core::sc_fifo_in<AddressEvent> in;
  std::vector<AddressEvent> got;
  std::vector<sc_core::sc_time> when;
  SC_HAS_PROCESS(Consumer);
  explicit Consumer(const sc_core::sc_module_name& name) : sc_module(name), in("in") { SC_THREAD(read); }
  void read() {
    for (;;) {
      got.push_back(in.read());
      when.push_back(sc_core::sc_time_stamp());
    }
  }
};

TEST(EventSource, HandsTheEventRungsEventsToAFifoAtTheirTimes) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = {{"sim.duration", "300ms"}, {"bus.t_event", "2us"}};
  const SimulationResult reference = reference_run(spec, "event");
  ASSERT_GT(reference.log.events().size(), 1000u);

  EventSource source("source", spec);
  Consumer consumer("consumer");
  sc_core::sc_fifo<AddressEvent> fifo("fifo", 16);
  source.out(fifo);
  consumer.in(fifo);
  std::size_t called = 0;
  source.on_event([&called](const AddressEvent&) { ++called; });
  sc_core::sc_start();
  const std::vector<AddressEvent>& want = reference.log.events();
  ASSERT_EQ(consumer.got.size(), want.size());
  EXPECT_EQ(called, want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    const AddressEvent& a = consumer.got[i];
    ASSERT_TRUE(a.t == want[i].t && a.x == want[i].x && a.y == want[i].y && a.tile == want[i].tile) << "event " << i;
    ASSERT_EQ(consumer.when[i].value(), static_cast<sc_dt::uint64>(std::llround(want[i].t * 1e12))) << "event " << i;
  }
  EXPECT_DOUBLE_EQ(source.tick(), 1e-6);
}

TEST(EventSource, RefusesTheCycleFidelityAndAReceiver) {
  ImagerSpec spec;
  spec.settings = {{"sim.fidelity", "cycle"}};
  EXPECT_THROW(EventSource("a", spec), InputError);
  spec.settings = {};
  spec.receiver = reference_receiver_factory();
  EXPECT_THROW(EventSource("b", spec), InputError);
}

}  // namespace
}  // namespace aesim
