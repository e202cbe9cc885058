#include "aesim/receiver/receiver_module.hpp"

#include <algorithm>
#include <cmath>

#include "aesim/receiver/receiver.hpp"

namespace aesim {
namespace {

class ReferenceReceiverModule : public ReceiverModule {
 public:
  ReferenceReceiverModule(const sc_core::sc_module_name& name, ReceiverSignals& s,
                          const ReceiverCycleModel::Config& config)
      : ReceiverModule(name), receiver_("model", config) {
    receiver_.bind(s);
  }

 private:
  Receiver receiver_;
};

}  // namespace

ReceiverFactory reference_receiver_factory() {
  return [](const std::string& name, std::uint32_t, ReceiverSignals& s, const ReceiverCycleModel::Config& config) {
    return std::make_unique<ReferenceReceiverModule>(name.c_str(), s, config);
  };
}

unsigned receiver_prescale(const ReceiverParams& receiver) {
  const double cycles = std::round(receiver.tick * receiver.clock);
  return static_cast<unsigned>(std::clamp(cycles, 1.0, static_cast<double>(kReceiverMaxPrescale)));
}

double receiver_tick(const ReceiverParams& receiver) { return receiver_prescale(receiver) / receiver.clock; }

ReceiverCycleModel::Config receiver_model_config(const ReceiverParams& receiver, bool discard_collisions,
                                                 const CycleOptions& options) {
  ReceiverCycleModel::Config c;
  c.addr_width = kReceiverAddrWidth;
  c.ts_width = kReceiverTsWidth;
  c.capacity = kReceiverFifoCapacity;
  c.hold_when_full = receiver.full_policy == FullPolicy::Hold;
  c.prescale = receiver_prescale(receiver);
  c.fifo_limit = static_cast<unsigned>(receiver.fifo_depth);
  c.discard_collisions = discard_collisions;
  c.ts_external = !options.free_running_clock;
  return c;
}

}  // namespace aesim
