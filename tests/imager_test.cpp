// The Imager module in a caller's own SystemC context, as a user's sc_main holds it: its events
// equal simulate()'s at the cycle fidelity, event for event (each test is a process of its own,
// so each gets the one elaboration and sc_start() SystemC allows a context).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <systemc>

#include "Vaer_receiver_drop.h"
#include "aesim/embed/event_source.hpp"
#include "aesim/embed/imager.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/receiver/receiver.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/scene/photocurrents.hpp"

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

// A caller's sc_main may set its own time resolution before the Imager is made: at 1 ns, which
// holds the receiver clock's 200 ns period, the run gives the events of simulate() at SystemC's
// default 1 ps (in a context of its own), event for event on this scene.
TEST(Imager, AtANanosecondResolutionTheClockHoldsAndTheEventsAreTheSame) {
  sc_core::sc_set_time_resolution(1, sc_core::SC_NS);
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = {{"sim.duration", "300ms"}, {"bus.t_event", "2us"}, {"receiver.clock", "5MHz"}};
  const SimulationResult reference = reference_run(spec, "cycle");
  Imager imager("imager", spec);
  sc_core::sc_start();
  const std::vector<AddressEvent>& events = imager.events();
  ASSERT_EQ(events.size(), reference.log.events().size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    const AddressEvent& a = events[i];
    const AddressEvent& b = reference.log.events()[i];
    ASSERT_TRUE(a.t == b.t && a.x == b.x && a.y == b.y && a.tile == b.tile && a.flags == b.flags) << "event " << i;
  }
}

// A resolution that cannot hold the clock's period as whole steps would move its edges (33 MHz,
// 30,303 ps, at 1 ns) or stop it (a period under two steps: the bus divided by a zero period):
// refused when the Imager is made, naming the resolution, the period and what to set.
TEST(Imager, ATimeResolutionThatCannotHoldTheClockIsRefusedWhenItIsMade) {
  sc_core::sc_set_time_resolution(1, sc_core::SC_NS);
  ImagerSpec spec;
  spec.settings = {{"sim.duration", "1ms"}, {"receiver.clock", "33MHz"}};
  try {
    Imager imager("a", spec);
    ADD_FAILURE() << "a 30303 ps clock made at a 1 ns resolution";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("SystemC's time resolution, 1 ns, cannot hold the receiver clock's period "
                                         "(30303 ps at receiver.clock 3.3e+07 Hz)"),
              std::string::npos)
        << e.what();
  }
  spec.settings = {{"sim.duration", "1ms"}, {"receiver.clock", "1GHz"}};  // one step a period
  EXPECT_THROW(Imager("b", spec), InputError);
  spec.settings = {{"sim.duration", "1ms"}, {"receiver.clock", "500MHz"}};  // two
  EXPECT_NO_THROW(Imager("c", spec));
}

// What `aesim run` warns of reaches the caller as SystemC reports: a calibrated preset whose range
// the scene's light leaves gives one SC_REPORT_WARNING per module, with the program's words, under
// the module's id; the caller's handler (here: keep it, print nothing) decides.
TEST(Imager, WarningsAreSystemCReportsUnderTheModulesId) {
  sc_core::sc_report_handler::set_actions(sc_core::SC_WARNING, sc_core::SC_CACHE_REPORT);
  ImagerSpec spec;
  spec.sensor = "aesim_pixel";
  spec.scene = std::string(AESIM_SOURCE_DIR) + "/scenes/gradient.pgm";
  spec.settings = {{"sim.duration", "1ms"}, {"pixel.i_max", "2nA"}};
  Imager imager("imager", spec);
  EXPECT_EQ(sc_core::sc_report_handler::get_count("aesim/Imager"), 1);
  const sc_core::sc_report* cached = sc_core::sc_report_handler::get_cached_report();
  ASSERT_NE(cached, nullptr);
  EXPECT_NE(std::string(cached->get_msg()).find("calibrated from 1 fA to 1 nA"), std::string::npos) << cached->get_msg();
  EventSource source("source", spec);
  EXPECT_EQ(sc_core::sc_report_handler::get_count("aesim/EventSource"), 1);
  spec.scene = std::string(AESIM_SOURCE_DIR) + "/scenes/uniform.pgm";  // 1 pA: inside the table
  spec.settings = {{"sim.duration", "1ms"}};
  Imager quiet("quiet", spec);
  EXPECT_EQ(sc_core::sc_report_handler::get_count("aesim/Imager"), 1);
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

// A receiver as a caller writes one, or as `verilator --sc` declares one: plain sc_in/sc_out ports
// named as rtl/aer_receiver.v's. Four-phase: Req through three flops (the last two decide), Ack
// raised with the address and the tick count taken, lowered when Req has fallen; a collision the
// bus flagged is acknowledged and dropped; one output register, emptied when the consumer is ready.
struct PortReceiver : sc_core::sc_module {
  sc_core::sc_in<bool> clk, rst_n, req, contention, evt_ready;
  sc_core::sc_in<std::uint32_t> addr, ts;
  sc_core::sc_out<bool> ack, idle, evt_valid, evt_flags;
  sc_core::sc_out<std::uint32_t> evt_addr, evt_ts;
  std::uint32_t taken = 0;
  SC_HAS_PROCESS(PortReceiver);
  explicit PortReceiver(const sc_core::sc_module_name& name) : sc_module(name) {
    SC_METHOD(on_clock);
    sensitive << clk.pos();
    dont_initialize();
  }
  void on_clock() {
    if (!rst_n.read()) return;
    const bool req_high = (sync_ & 0b110) == 0b110, req_low = (sync_ & 0b110) == 0;
    if (full_ && evt_ready.read()) full_ = false;
    if (!acking_ && req_high) {
      acking_ = true;
      if (!contention.read()) {
        full_ = true;
        ++taken;
        addr_ = addr.read();
        ts_ = ts.read();
      }
    } else if (acking_ && req_low) {
      acking_ = false;
    }
    sync_ = ((sync_ << 1) | (req.read() ? 1u : 0u)) & 0b111;
    ack.write(acking_);
    evt_valid.write(full_);
    evt_addr.write(full_ ? addr_ : 0);
    evt_ts.write(full_ ? ts_ : 0);
    evt_flags.write(false);
    idle.write(!acking_ && !full_ && sync_ == 0);
  }
  unsigned sync_ = 0;
  bool acking_ = false, full_ = false;
  std::uint32_t addr_ = 0, ts_ = 0;
};

// The caller's signals between tile `t`'s ports and a PortReceiver; the stream and idle only when
// `whole`.
struct Wiring {
  sc_core::sc_signal<bool> clk, rst_n, req, contention, evt_ready, ack, idle, evt_valid, evt_flags;
  sc_core::sc_signal<std::uint32_t> addr, ts, evt_addr, evt_ts;
  PortReceiver rx{"my_receiver"};
  Wiring(TilePorts& p, bool whole) {
    p.clk(clk), rx.clk(clk);
    p.rst_n(rst_n), rx.rst_n(rst_n);
    p.req(req), rx.req(req);
    p.contention(contention), rx.contention(contention);
    p.addr(addr), rx.addr(addr);
    p.ts(ts), rx.ts(ts);
    p.ack(ack), rx.ack(ack);
    rx.idle(idle), rx.evt_valid(evt_valid), rx.evt_flags(evt_flags), rx.evt_addr(evt_addr), rx.evt_ts(evt_ts);
    rx.evt_ready(evt_ready);
    if (whole) {
      p.idle(idle), p.evt_valid(evt_valid), p.evt_flags(evt_flags), p.evt_addr(evt_addr), p.evt_ts(evt_ts);
      p.evt_ready(evt_ready);
    } else {
      evt_ready.write(true);  // the caller's own consumer, always ready
    }
  }
};

// The tile that delivered the most events in `run`.
std::uint32_t busiest_tile(const SimulationResult& run) {
  std::vector<std::size_t> n(4);
  for (const AddressEvent& e : run.log.events()) ++n.at(e.tile);
  return static_cast<std::uint32_t>(std::max_element(n.begin(), n.end()) - n.begin());
}

// Every event of `got` equal to `want`'s (time, pixel, tile, flags), in order; `on_tile` counts
// those of tile `tile`.
void expect_same_events(const std::vector<AddressEvent>& got, const std::vector<AddressEvent>& want, std::uint32_t tile,
                        std::size_t& on_tile) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    const AddressEvent& a = got[i];
    const AddressEvent& b = want[i];
    ASSERT_TRUE(a.t == b.t && a.x == b.x && a.y == b.y && a.tile == b.tile && a.flags == b.flags) << "event " << i;
    on_tile += a.tile == tile;
  }
}

const std::vector<Setting> kLoadedBus = {{"sim.duration", "300ms"}, {"bus.t_event", "2us"}, {"receiver.clock", "5MHz"}};

// The busiest tile's receiver outside the Imager, wired to its ports through the caller's sc_signals, with
// idle and the output stream connected: the same events as simulate() with aesim's receiver on
// every tile, event for event (the receiver keeps the reference's timing).
TEST(Imager, ATileWiredToAReceiverOutsideGivesTheSameEvents) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = kLoadedBus;
  const SimulationResult reference = reference_run(spec, "cycle");
  const std::uint32_t t = busiest_tile(reference);
  spec.outside_receivers = {t};

  Imager imager("imager", spec);
  Wiring wiring(imager.tile[t], true);
  sc_core::sc_start();
  std::size_t on_t = 0;
  ASSERT_NO_FATAL_FAILURE(expect_same_events(imager.events(), reference.log.events(), t, on_t));
  EXPECT_GT(on_t, 1000u);
  EXPECT_EQ(wiring.rx.taken, on_t);
  EXPECT_EQ(imager.protocol_violations(), 0u);
  EXPECT_LE(sc_core::sc_time_stamp().to_seconds(), 0.3);  // idle stopped the clock: the kernel starved
}

// With Ack, Req, address and clock alone connected (no idle, no stream): the clock runs free until
// sim.duration and stops once the handshake is done, so sc_start() returns; the receiver took
// every event aesim's receiver delivers on that tile, and the Imager's own record of the tile holds
// none (what an outside receiver delivers is the caller's).
TEST(Imager, AnOutsideReceiverWithoutIdleOrStreamStillEndsTheRun) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = kLoadedBus;
  const SimulationResult reference = reference_run(spec, "cycle");
  const std::uint32_t t = busiest_tile(reference);
  spec.outside_receivers = {t};
  std::size_t want = 0;
  for (const AddressEvent& e : reference.log.events()) want += e.tile == t;

  Imager imager("imager", spec);
  Wiring wiring(imager.tile[t], false);
  sc_core::sc_start();
  EXPECT_GE(sc_core::sc_time_stamp().to_seconds(), 0.3);
  EXPECT_LT(sc_core::sc_time_stamp().to_seconds(), 0.3001);
  EXPECT_EQ(wiring.rx.taken, want);
  EXPECT_GT(want, 1000u);
  for (const AddressEvent& e : imager.events()) ASSERT_NE(e.tile, t);
  EXPECT_EQ(imager.protocol_violations(), 0u);
}

// The receiver RTL Verilated with `verilator --sc` (aesim's own, rtl/aer_receiver.v) outside the
// Imager, every port bound to the caller's sc_signals as a hardware team wires their own: the same
// events as simulate() with the reference model on every tile, no rule broken (the counters are
// connected, so nothing may vanish either).
TEST(Imager, AVerilatedReceiverOnTheTilePortsGivesTheSameEvents) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = kLoadedBus;
  const SimulationResult reference = reference_run(spec, "cycle");
  const std::uint32_t t = busiest_tile(reference);
  spec.outside_receivers = {t};

  Imager imager("imager", spec);
  TilePorts& p = imager.tile[t];
  Vaer_receiver_drop rtl("rtl");
  sc_core::sc_signal<bool> clk, rst_n, req, contention, ack, discard, ts_external, valid, ready, flags, idle;
  sc_core::sc_signal<std::uint32_t> addr, prescale, fifo_limit, ts, evt_ts, evt_addr, events, collisions, overflows,
      fifo_count;
  p.clk(clk), rtl.clk_i(clk);
  p.rst_n(rst_n), rtl.rst_ni(rst_n);
  p.req(req), rtl.req_i(req);
  p.addr(addr), rtl.addr_i(addr);
  p.contention(contention), rtl.contention_i(contention);
  p.ack(ack), rtl.ack_o(ack);
  p.prescale(prescale), rtl.prescale_i(prescale);
  p.fifo_limit(fifo_limit), rtl.fifo_limit_i(fifo_limit);
  p.discard_collisions(discard), rtl.discard_collisions_i(discard);
  p.ts_external(ts_external), rtl.ts_external_i(ts_external);
  p.ts(ts), rtl.ts_i(ts);
  p.evt_valid(valid), rtl.evt_valid_o(valid);
  p.evt_ready(ready), rtl.evt_ready_i(ready);
  p.evt_ts(evt_ts), rtl.evt_ts_o(evt_ts);
  p.evt_addr(evt_addr), rtl.evt_addr_o(evt_addr);
  p.evt_flags(flags), rtl.evt_flags_o(flags);
  p.events(events), rtl.events_o(events);
  p.fifo_count(fifo_count), rtl.fifo_count_o(fifo_count);
  p.idle(idle), rtl.idle_o(idle);
  rtl.collisions_o(collisions);
  rtl.overflows_o(overflows);
  sc_core::sc_start();

  std::size_t on_t = 0;
  ASSERT_NO_FATAL_FAILURE(expect_same_events(imager.events(), reference.log.events(), t, on_t));
  EXPECT_GT(on_t, 1000u);
  EXPECT_EQ(events.read(), on_t);  // the RTL's own count
  EXPECT_EQ(imager.protocol_violations(), 0u);
}

// A design that never starves (the caller's own free-running clock) runs the Imager in slices of
// sc_start(T): read before the run is done, the record refuses (it would stop there and lose what
// is still to come); read after it, it holds every event of the run.
TEST(Imager, ReadBeforeTheRunIsDoneItRefusesAfterItHoldsEveryEvent) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = kLoadedBus;
  const SimulationResult reference = reference_run(spec, "cycle");
  sc_core::sc_clock clock("callers_clock", 1, sc_core::SC_US);
  Imager imager("imager", spec);
  sc_core::sc_start(100, sc_core::SC_MS);
  try {
    imager.events();
    ADD_FAILURE() << "events() gave a record at 100 ms of a 300 ms run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the run is not done at 100 ms"), std::string::npos) << e.what();
  }
  sc_core::sc_start(250, sc_core::SC_MS);
  std::size_t on_0 = 0;
  ASSERT_NO_FATAL_FAILURE(expect_same_events(imager.events(), reference.log.events(), 0, on_0));
}

// aesim's bundled receiver as a module (aesim::Receiver) outside the Imager on every tile, each
// wired through the caller's sc_signals: on tiles 0 and 1 with the settings' ports bound to the
// tile's (the receiver reads them at reset, as the RTL does), on 2 and 3 with the settings from
// receiver_config() alone. The same events as simulate() with the Imager's own receivers; the bus
// wires traced into the caller's VCD file change as often as there were transactions.
TEST(Imager, TheBundledReceiverOnEveryTilesPortsGivesTheSameEventsAndTracesItsWires) {
  ImagerSpec spec;
  spec.scene = kScene;
  spec.settings = kLoadedBus;
  const SimulationResult reference = reference_run(spec, "cycle");
  spec.outside_receivers = {0, 1, 2, 3};

  Imager imager("imager", spec);
  struct Wires {
    sc_core::sc_signal<bool> clk, rst_n, req, contention, ack, discard, ts_external, valid, ready, flags, idle;
    sc_core::sc_signal<std::uint32_t> addr, prescale, fifo_limit, ts, evt_ts, evt_addr, events, fifo_count;
  };
  std::vector<std::unique_ptr<Wires>> wires;
  std::vector<std::unique_ptr<Receiver>> receivers;
  for (std::uint32_t t = 0; t < 4; ++t) {
    wires.push_back(std::make_unique<Wires>());
    Wires& w = *wires.back();
    receivers.push_back(std::make_unique<Receiver>(("rx" + std::to_string(t)).c_str(), imager.receiver_config()));
    Receiver& rx = *receivers.back();
    TilePorts& p = imager.tile[t];
    p.clk(w.clk), rx.clk(w.clk);
    p.rst_n(w.rst_n), rx.rst_n(w.rst_n);
    p.req(w.req), rx.req(w.req);
    p.addr(w.addr), rx.addr(w.addr);
    p.contention(w.contention), rx.contention(w.contention);
    p.ack(w.ack), rx.ack(w.ack);
    p.ts(w.ts), rx.ts(w.ts);
    p.evt_valid(w.valid), rx.evt_valid(w.valid);
    p.evt_ready(w.ready), rx.evt_ready(w.ready);
    p.evt_ts(w.evt_ts), rx.evt_ts(w.evt_ts);
    p.evt_addr(w.evt_addr), rx.evt_addr(w.evt_addr);
    p.evt_flags(w.flags), rx.evt_flags(w.flags);
    p.events(w.events), rx.events(w.events);
    p.fifo_count(w.fifo_count), rx.fifo_count(w.fifo_count);
    p.idle(w.idle), rx.idle(w.idle);
    if (t < 2) {
      p.prescale(w.prescale), rx.prescale(w.prescale);
      p.fifo_limit(w.fifo_limit), rx.fifo_limit(w.fifo_limit);
      p.discard_collisions(w.discard), rx.discard_collisions(w.discard);
      p.ts_external(w.ts_external), rx.ts_external(w.ts_external);
    }
  }
  const std::string vcd = ::testing::TempDir() + "imager_trace";
  sc_core::sc_trace_file* file = sc_core::sc_create_vcd_trace_file(vcd.c_str());
  file->set_time_unit(1, sc_core::SC_PS);
  imager.trace(file);
  sc_core::sc_start();
  sc_core::sc_close_vcd_trace_file(file);

  std::size_t on_0 = 0;
  ASSERT_NO_FATAL_FAILURE(expect_same_events(imager.events(), reference.log.events(), 0, on_0));
  EXPECT_EQ(imager.protocol_violations(), 0u);
  std::uint64_t delivered = 0;
  for (const auto& w : wires) delivered += w->events.read();
  EXPECT_EQ(delivered, reference.log.events().size());

  // The VCD holds each tile's wires in a scope of its own (imager.tile<t>), and tile 0's Ack rises
  // once per transaction it answered: at least once per event it delivered.
  std::ifstream in(vcd + ".vcd");
  ASSERT_TRUE(in.good());
  std::string line, scope, ack_code;
  std::size_t ack_rises = 0;
  bool tile3_req = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string first, type, width, code, name;
    words >> first;
    if (first == "$scope") {
      words >> type >> scope;
    } else if (first == "$var") {
      words >> type >> width >> code >> name;
      if (scope == "tile0" && name == "ack") ack_code = code;
      if (scope == "tile3" && name == "req") tile3_req = true;
    } else if (!ack_code.empty() && line == "1" + ack_code) {
      ++ack_rises;
    }
  }
  EXPECT_TRUE(tile3_req);
  ASSERT_FALSE(ack_code.empty());
  EXPECT_GE(ack_rises, on_0);
}

TEST(Imager, TilePortsBoundWrongAreReportedAtElaboration) {
  ImagerSpec spec;
  spec.outside_receivers = {4};
  EXPECT_THROW(Imager("a", spec), InputError);  // the aloha sensor has tiles 0 to 3
  spec.outside_receivers = {1};
  Imager imager("imager", spec);
  sc_core::sc_signal<bool> ack("ack");
  sc_core::sc_signal<bool> ack1("ack1");
  imager.tile[1].ack(ack1);
  imager.tile[2].ack(ack);  // tile 2 has aesim's receiver
  try {
    sc_core::sc_start();
    FAIL() << "sc_start() accepted ports bound to a tile with aesim's receiver";
  } catch (const sc_core::sc_report& r) {
    EXPECT_NE(std::string(r.what()).find("tile 2 has aesim's receiver"), std::string::npos) << r.what();
  }
}

TEST(Imager, AnOutsideReceiverWithoutAckIsReported) {
  ImagerSpec spec;
  spec.outside_receivers = {1};
  Imager imager("imager", spec);
  try {
    sc_core::sc_start();
    FAIL() << "sc_start() ran with tile 1's Ack unconnected";
  } catch (const sc_core::sc_report& r) {
    EXPECT_NE(std::string(r.what()).find("imager.tile_1.ack is not bound"), std::string::npos) << r.what();
  }
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
  spec.receiver = nullptr;
  spec.outside_receivers = {0};
  EXPECT_THROW(EventSource("c", spec), InputError);
}

}  // namespace
}  // namespace aesim
