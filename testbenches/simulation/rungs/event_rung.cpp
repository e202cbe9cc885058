#include <algorithm>
#include <atomic>
#include <thread>

#include "array/firing_schedule.hpp"
#include "rungs/event_level_buses.hpp"
#include "rungs/rung.hpp"

namespace aesim {
namespace {

// sim.fidelity=event: the exact event-driven reference. Every tile's firings come out of its
// FiringSchedule in time order, straight into its event-level bus, with no SystemC time (nothing
// else observes them); tiles on up to sim.threads threads.
class EventRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::Event; }
  RungCapabilities capabilities() const override {
    RungCapabilities can;
    can.exact = true;
    return can;
  }
  void run(const RungRun& run, RunFacts& facts) const override {
    EventLevelBuses buses(run);
    const int tiles = run.map.tiles();
    int threads = run.config.sim.threads;
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, tiles);
    std::atomic<int> next_tile{0};
    auto work = [&] {
      for (int t = next_tile++; t < tiles; t = next_tile++) {
        FiringSchedule schedule(run.config.pixel, run.config.sim, run.photocurrents, run.map, static_cast<std::uint32_t>(t));
        EventBus& bus = buses[static_cast<std::size_t>(t)];
        AddressEvent firing;
        while (schedule.next(firing)) bus.request(firing);
      }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& th : pool) th.join();
    buses.finish(run.config.bus, facts);
  }
};

}  // namespace

const Rung& event_rung() {
  static const EventRung rung;
  return rung;
}

}  // namespace aesim
