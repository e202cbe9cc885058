#include "aesim/rungs/cycle_array.hpp"

#include <fmt/format.h>

#include "aesim/array/schedule_driver.hpp"
#include "aesim/cosim/rtl_receiver.hpp"
#include "aesim/cosim/stepped_rtl_receiver.hpp"

namespace aesim {

CycleArray::CycleArray(const sc_core::sc_module_name& name, const RungRun& run, const CycleOptions& options)
    : sc_module(name) {
  std::vector<EventBus*> buses;
  for (int t = 0; t < run.map.tiles(); ++t) {
    tiles_.push_back(std::make_unique<CycleTile>(fmt::format("tile{}", t).c_str(), static_cast<std::uint32_t>(t),
                                                 run.map, run.config, run.log, run.vcd, options));
    buses.push_back(&tiles_.back()->bus());
  }
  driver_ = std::make_unique<ScheduleDriver>("schedule", run.config.pixel, run.config.sim, run.photocurrents, run.map,
                                             std::move(buses));
  for (std::size_t t = 0; t < tiles_.size(); ++t) {
    tiles_[t]->set_next_firing([driver = driver_.get(), t] { return driver->next_firing_ps(t); });
  }
}

CycleArray::~CycleArray() = default;

bool CycleArray::done() const {
  if (!driver_->all_fired()) return false;
  for (const auto& tile : tiles_) {
    if (!tile->quiescent()) return false;
  }
  return true;
}

CycleOptions cycle_options(const RungRun& run) {
  CycleOptions options = run.request.cycle;
  if (!options.receiver && !options.stepped_receiver && run.config.receiver.model == ReceiverModel::Rtl) {
    const FullPolicy policy = run.config.receiver.full_policy;
    if (run.request.rtl_trace_path) {
      // Tracing the RTL's internal signals: the Verilated SystemC model on the tile's clock wire.
      options.receiver = rtl_receiver_factory(policy, run.request.rtl_trace_path,
                                              sc_core::sc_time(run.request.vcd_from, sc_core::SC_SEC),
                                              sc_core::sc_time(run.request.vcd_to, sc_core::SC_SEC));
    } else {
      options.stepped_receiver = [policy](std::uint32_t, const ReceiverCycleModel::Config& config) {
        return make_stepped_rtl_receiver(policy, config);
      };
    }
  }
  return options;
}

}  // namespace aesim
