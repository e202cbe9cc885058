#pragma once
#include <functional>
#include <memory>
#include <systemc>
#include <vector>

#include "array/address_map.hpp"
#include "bus/tile_bus.hpp"
#include "waveform/vcd_recorder.hpp"
#include "pixel/pixel.hpp"
#include "events/event_log.hpp"
#include "receiver/receiver_module.hpp"

namespace aesim {

// The pixel array split into tiles, each tile with its own bus. The bus model follows
// bus.access and the fidelity. At the pixel_processes fidelity every pixel is a SystemC module
// bound to its tile's bus; at the cycle fidelity one ScheduleDriver process feeds the clocked
// buses from the tiles' FiringSchedules; at the event fidelity no SystemC process runs at all and
// run_schedule() feeds each bus from its tile's schedule.
class Imager : public sc_core::sc_module {
 public:
  Imager(const sc_core::sc_module_name& name, const SensorConfig& config, Fidelity fidelity,
         const Photocurrents& light, EventLog& log, VcdRecorder* vcd, const CycleOptions& cycle = {});

  // The event fidelity: every tile's firings, in time order, straight into its bus, with no
  // SystemC time (nothing else observes them); tiles on up to `threads` threads.
  void run_schedule(const Photocurrents& light, int threads);
  // The queue fidelity: the paper's event queue, in queue order, into the buses.
  void run_queue(const Photocurrents& light);
  // Steps where a fixed_step pixel crossed its threshold more than once (0 at other rungs).
  std::uint64_t multi_fire_steps() const;
  // Lit frames the queue model had to leave empty (0 at other rungs).
  std::uint64_t empty_queue_frames() const { return empty_queue_frames_; }
  // After the run: lets every bus settle what it still holds.
  void finish();
  // Mean bus transaction time: measured by clocked buses, bus.t_event otherwise.
  double tau() const;
  // Totals over the clocked buses (all zero below the cycle fidelity): handshake and stream rule
  // breaks seen by the monitors, receiver clock edges simulated, and the co-simulation
  // scoreboard's compared beats and mismatches (RTL receivers only).
  struct CycleStats {
    std::uint64_t protocol_violations = 0, clock_edges = 0, scoreboard_beats = 0, scoreboard_mismatches = 0;
  };
  CycleStats cycle_stats() const;

 private:
  const SensorConfig& config_;
  AddressMap map_;
  std::vector<std::unique_ptr<TileBus>> buses_;
  std::vector<std::unique_ptr<Pixel>> pixels_;
  std::unique_ptr<sc_core::sc_module> driver_;
  std::uint64_t empty_queue_frames_ = 0;
};

}  // namespace aesim
