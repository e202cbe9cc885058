#include "receiver/receiver_module.hpp"

#include <algorithm>
#include <cmath>

#include "receiver/reference_receiver.hpp"

namespace aesim {
namespace {

class ReferenceReceiverModule : public ReceiverModule {
 public:
  ReferenceReceiverModule(const sc_core::sc_module_name& name, ReceiverSignals& s,
                          const ReceiverCycleModel::Config& config)
      : ReceiverModule(name), receiver_("model", s, config) {}

 private:
  ReferenceReceiver receiver_;
};

}  // namespace

ReceiverFactory reference_receiver_factory() {
  return [](const std::string& name, ReceiverSignals& s, const ReceiverCycleModel::Config& config) {
    return std::make_unique<ReferenceReceiverModule>(name.c_str(), s, config);
  };
}

unsigned receiver_prescale(const SensorConfig& config) {
  const double cycles = std::round(config.receiver.tick * config.receiver.clock);
  return static_cast<unsigned>(std::clamp(cycles, 1.0, static_cast<double>(kReceiverMaxPrescale)));
}

double receiver_tick(const SensorConfig& config) { return receiver_prescale(config) / config.receiver.clock; }

ReceiverCycleModel::Config receiver_model_config(const SensorConfig& config, const CycleOptions& options) {
  ReceiverCycleModel::Config c;
  c.addr_width = kReceiverAddrWidth;
  c.ts_width = kReceiverTsWidth;
  c.capacity = kReceiverFifoCapacity;
  c.hold_when_full = config.receiver.full_policy == FullPolicy::Hold;
  c.prescale = receiver_prescale(config);
  c.fifo_limit = static_cast<unsigned>(config.receiver.fifo_depth);
  c.discard_collisions = config.bus.contention_detect;
  c.ts_external = !options.free_running_clock;
  return c;
}

}  // namespace aesim
