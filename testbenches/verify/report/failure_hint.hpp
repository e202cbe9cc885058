#pragma once
#include <string>
#include <vector>

#include "description/receiver_description.hpp"
#include "scoreboard/transaction_scoreboard.hpp"

namespace aesim {

// What a first failure usually means when a correct design fails it, and the description key that
// says so; empty where no such cause is common. A failure of the design itself reads the same,
// so a hint says where to look, never that the design is right.
// `held_at_zero`: the design's inputs the description leaves alone (inputs_held_at_zero).
std::string failure_hint(const VerifyFailure& f, const ReceiverDescription& d, const std::vector<std::string>& held_at_zero);

}  // namespace aesim
