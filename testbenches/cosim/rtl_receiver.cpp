#include "cosim/rtl_receiver.hpp"

#include "Vaer_receiver_drop.h"
#include "Vaer_receiver_hold.h"

namespace aesim {

ReceiverFactory rtl_receiver_factory(FullPolicy policy) {
  return [policy](const std::string& name, ReceiverSignals& s,
                  const ReceiverCycleModel::Config& config) -> std::unique_ptr<ReceiverModule> {
    if (policy == FullPolicy::Hold) return std::make_unique<RtlReceiver<Vaer_receiver_hold>>(name.c_str(), s, config);
    return std::make_unique<RtlReceiver<Vaer_receiver_drop>>(name.c_str(), s, config);
  };
}

}  // namespace aesim
