#pragma once
#include <vector>

#include "description/receiver_description.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

// The protocol's corner cases, timed from the description's clock and Ack latency: a single
// event, back-to-back transactions, a Req glitch straddling a clock edge, a collision, a reset in
// the middle of a handshake, long back-pressure, and an output held full.
std::vector<VerifyCase> directed_cases(const ReceiverDescription& d);

}  // namespace aesim
