#pragma once
#include <memory>
#include <string>
#include <vector>

#include <systemc>

#include "aesim/config/sensor_config.hpp"
#include "aesim/embed/tile_ports.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/receiver/receiver_module.hpp"
#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

class CycleArray;

// What an Imager is built from, as `aesim run` takes it: a preset, a scene, --set settings.
struct ImagerSpec {
  std::string sensor = "aloha";   // a preset's name (models/sensors) or a .toml file
  std::string scene;              // an image file or a frame folder; empty: scenes/letters/A.pgm
  std::vector<Setting> settings;  // {"pixel.c_int", "50fF"}, ... applied in order (later wins)
  // Each tile's receiver, made by the caller: a module bound to the tile's ReceiverSignals (clk,
  // rst_n, the bus's req, addr and contention, ack; the tick count on ts; the output stream
  // evt_valid/ready/ts/addr/flags; idle, which lets the tile stop the clock). Empty: aesim's own
  // (the reference model, or the RTL with receiver.model=rtl). reference_receiver_factory()
  // makes the reference model for the tiles a caller does not replace.
  ReceiverFactory receiver;
  // Tiles whose receiver lives outside the Imager: the caller connects it to Imager::tile[t]'s
  // ports through sc_signals (at least `ack`), and the factory is not asked for these tiles.
  std::vector<std::uint32_t> outside_receivers;
};

// What an ImagerSpec names, for a module of fidelity `rung`: its configuration (sim.fidelity must be
// `rung` or auto, else InputError saying `use_instead`; the rung's own checks passed) and the
// scene's photocurrents. Shared by the embeddable modules. What `aesim run` would warn of (the
// scene's light outside a calibrated preset's range) is reported as SC_REPORT_WARNING with the
// module's `report_id`, so the caller's report handler decides what becomes of it.
struct SpecInputs {
  ResolvedConfig config;
  Photocurrents photocurrents;
};
SpecInputs spec_inputs(const ImagerSpec& spec, Fidelity rung, const char* use_instead, const char* report_id);

// The imager at the cycle fidelity as a SystemC module for the caller's own sc_main: the pixels
// of every tile firing onto their tile's clocked ALOHA bus (Req/Ack, 10-bit address, contention)
// and the tile's receiver (the reference model, or the receiver RTL with receiver.model=rtl). It
// is built in the current simulation context and runs under the caller's sc_start(); once the
// scene's sim.duration is simulated and the last handshake is done, it stops its processes and
// clocks, so a plain sc_start() returns. The same preset, scene and settings give the same events
// as `aesim run --set sim.fidelity=cycle`, event for event.
//
// Bad input (an unknown key, a scene that does not read, a fidelity other than cycle) throws
// InputError naming it, from the constructor, before anything is elaborated.
class Imager : public sc_core::sc_module {
 public:
  Imager(const sc_core::sc_module_name& name, const ImagerSpec& spec);
  ~Imager() override;

  // Each tile's bus as ports (TilePorts), bound only for the tiles named in
  // ImagerSpec::outside_receivers.
  sc_core::sc_vector<TilePorts> tile;
  Imager(const Imager&) = delete;
  Imager& operator=(const Imager&) = delete;

  // The configuration the run uses (the preset with the settings applied and resolved).
  const ResolvedConfig& config() const;
  // The receivers' timestamp resolution, s (receiver.tick): the step of the delivered stamps.
  double tick() const;
  // How aesim's own receiver is set up on this imager's tiles (widths, FIFO, full policy,
  // prescale, collisions, stamps from the tile's `ts`): what an aesim::Receiver on a tile's ports
  // is built with to behave as the Imager's own.
  ReceiverCycleModel::Config receiver_config() const;
  // Adds every tile's bus wires to the caller's trace file (sc_create_vcd_trace_file), named
  // <this module>.tile<t>.<wire>: req, addr, contention and ack of every tile, and for a tile whose
  // receiver is on a clock wire (outside the Imager, or from ImagerSpec::receiver) the clock, reset,
  // idle and output stream too. Call during elaboration, as sc_trace requires.
  void trace(sc_core::sc_trace_file* file) const override;

  // After sc_start() has returned with the run done (every firing of sim.duration on its bus and
  // every handshake over; an sc_start(T) that stops earlier leaves it undone, and these throw
  // InputError saying so): what the receivers delivered, in (time, tile, address) order, each `t`
  // the delivery time; and each tile's counters.
  const std::vector<AddressEvent>& events();
  std::vector<TileCounters> tiles();
  // Handshakes that broke the bus's rules (Ack without Req, Ack too early or late, a stream beat
  // that moved while stalled), over all tiles: 0 for a receiver that keeps them.
  std::uint64_t protocol_violations() const;

 private:
  struct Run;
  std::unique_ptr<Run> run_;
  std::unique_ptr<CycleArray> array_;
  bool finished_ = false;
  void finish();
};

}  // namespace aesim
