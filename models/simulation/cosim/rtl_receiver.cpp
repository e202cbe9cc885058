#include "aesim/cosim/rtl_receiver.hpp"

#include "Vaer_receiver_drop.h"
#include "Vaer_receiver_hold.h"

namespace aesim {

namespace {

template <class V>
std::unique_ptr<ReceiverModule> make(const std::string& name, ReceiverSignals& s,
                                     const ReceiverCycleModel::Config& config, const RtlTrace* trace) {
  auto rx = std::make_unique<RtlReceiver<V>>(name.c_str(), s, config);
  if (trace) rx->trace_internals(*trace);
  return rx;
}

}  // namespace

ReceiverFactory rtl_receiver_factory(FullPolicy policy, std::function<std::string(int)> trace_path,
                                     sc_core::sc_time from, sc_core::sc_time to) {
  return [=](const std::string& name, std::uint32_t tile, ReceiverSignals& s,
             const ReceiverCycleModel::Config& config) -> std::unique_ptr<ReceiverModule> {
    RtlTrace trace{trace_path ? trace_path(static_cast<int>(tile)) : std::string(), from, to};
    const RtlTrace* t = trace_path ? &trace : nullptr;
    if (policy == FullPolicy::Hold) return make<Vaer_receiver_hold>(name, s, config, t);
    return make<Vaer_receiver_drop>(name, s, config, t);
  };
}

}  // namespace aesim
