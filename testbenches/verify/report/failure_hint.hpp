#pragma once
#include <string>

#include "description/receiver_description.hpp"
#include "scoreboard/transaction_scoreboard.hpp"

namespace aesim {

// What a first failure usually means when a correct design fails it, and the description key that
// says so; empty where no such cause is common. A failure of the design itself reads the same,
// so a hint says where to look, never that the design is right.
std::string failure_hint(const VerifyFailure& f, const ReceiverDescription& d);

}  // namespace aesim
