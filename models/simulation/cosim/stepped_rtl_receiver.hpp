#pragma once
#include <functional>
#include <memory>

#include "aesim/config/sensor_config.hpp"
#include "aesim/receiver/receiver_cycle_model.hpp"
#include "aesim/receiver/stepped_receiver.hpp"

namespace aesim {

// rtl/aer_receiver.v Verilated as a plain C++ model (no SystemC ports), stepped by the tile's clock
// domain edge after edge within one SystemC activation, with the co-simulation scoreboard: the
// reference ReceiverCycleModel clocked beside it with the same inputs, every output compared after
// each edge. The same edges, inputs and results as the RTL on a clock wire (cosim/rtl_receiver),
// at a fraction of the cost; that one stays for runs that trace the RTL's internal signals.
std::unique_ptr<SteppedReceiver> make_stepped_rtl_receiver(FullPolicy policy, const ReceiverCycleModel::Config& config);

}  // namespace aesim
