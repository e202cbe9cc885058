#pragma once
#include <cstdint>
#include <memory>
#include <systemc>
#include <vector>

#include "aesim/array/firing_schedule.hpp"
#include "aesim/bus/event_bus.hpp"
#include "aesim/containers/min_heap.hpp"

namespace aesim {

// Feeds clocked buses from the tiles' FiringSchedules with a single SystemC process: it advances
// SystemC time only to the next firing of any tile, where the bus wires must see it. Replaces a
// process per pixel at the cycle fidelity.
class ScheduleDriver : public sc_core::sc_module {
 public:
  ScheduleDriver(const sc_core::sc_module_name& name, const PixelParams& pixel, const SimParams& sim,
                 const Photocurrents& photocurrents, const AddressMap& map, std::vector<EventBus*> buses);
  SC_HAS_PROCESS(ScheduleDriver);

  // When (ps, as the bus sees it) tile `tile`'s next firing drives its wires; ~0 when none is left.
  std::uint64_t next_firing_ps(std::size_t tile) const { return next_ps_[tile]; }
  // Whether every firing of the run has been handed to its bus.
  bool all_fired() const { return heads_.empty(); }

 private:
  void run();
  static constexpr std::uint64_t kNone = ~std::uint64_t(0);
  // The firing's time on SystemC's grid, rounded as sc_time(t, SC_SEC) rounds it (t times the
  // ticks a second, plus a half, truncated), without that constructor's library call per firing.
  std::uint64_t at_ps(const AddressEvent& firing) const {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(firing.t * ticks_per_s_ + 0.5));
  }
  double ticks_per_s_;  // of SystemC's time resolution

  struct Head {
    AddressEvent firing;
    std::size_t tile;
  };
  // Time order; simultaneous firings by tile, then bus address.
  struct Before {
    bool operator()(const Head& a, const Head& b) const;
  };
  std::vector<std::unique_ptr<FiringSchedule>> schedules_;
  std::vector<EventBus*> buses_;
  MinHeap<Head, Before, 2> heads_;  // each tile's next firing
  std::vector<std::uint64_t> next_ps_;  // per tile, its next firing's time in ps
};

}  // namespace aesim
