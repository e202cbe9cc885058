#include <memory>
#include <vector>

#include <fmt/format.h>

#include "aesim/bus/pixel_bus_if.hpp"
#include "aesim/kernel/systemc_kernel.hpp"
#include "aesim/pixel/pixel_process.hpp"
#include "aesim/rungs/event_level_buses.hpp"
#include "aesim/rungs/rung.hpp"

namespace aesim {
namespace {

// The array as a SystemC engineer would write it first: every pixel a SystemC module with exact
// times, bound to its tile's bus port.
class PixelArray : public sc_core::sc_module {
 public:
  PixelArray(const sc_core::sc_module_name& name, const RungRun& run, EventLevelBuses& buses) : sc_module(name) {
    for (int t = 0; t < run.map.tiles(); ++t) {
      ports_.push_back(std::make_unique<PixelBusPort>(fmt::format("tile{}", t).c_str(),
                                                      buses[static_cast<std::size_t>(t)]));
    }
    pixels_.reserve(run.photocurrents.pixels());
    for (int y = 0; y < run.map.rows(); ++y) {
      for (int x = 0; x < run.map.cols(); ++x) {
        const AddressEvent identity = run.map.event_at({static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)});
        const std::size_t index = static_cast<std::size_t>(y) * run.map.cols() + x;
        auto pixel = std::make_unique<PixelProcess>(fmt::format("px_{}_{}", x, y).c_str(), run.config.pixel, run.config.sim,
                                                    run.photocurrents, index, identity);
        pixel->bus.bind(*ports_[identity.tile]);
        pixels_.push_back(std::move(pixel));
      }
    }
  }

 private:
  std::vector<std::unique_ptr<PixelBusPort>> ports_;
  std::vector<std::unique_ptr<PixelProcess>> pixels_;
};

// sim.fidelity=pixel_processes: the baseline with a SystemC process per pixel; the same results as
// the event rung, at the cost of the kernel's scheduling.
class PixelProcessesRung : public Rung {
 public:
  Fidelity fidelity() const override { return Fidelity::PixelProcesses; }
  RungCapabilities capabilities() const override {
    RungCapabilities can;
    can.exact = true;
    return can;
  }
  void run(const RungRun& run, RunFacts& facts) const override {
    const ScopedKernel kernel;  // first, so the modules are gone before their context
    EventLevelBuses buses(run);
    PixelArray array("imager", run, buses);
    // Every pixel stops scheduling itself past sim.duration, so the kernel starves when done.
    run_until_starved(run.config.sim.duration);
    buses.finish(run.config.bus, facts);
  }
};

}  // namespace

const Rung& pixel_processes_rung() {
  static const PixelProcessesRung rung;
  return rung;
}

}  // namespace aesim
