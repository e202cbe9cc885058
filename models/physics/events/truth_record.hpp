#pragma once
#include <cstdint>

#include "aesim/events/address_event.hpp"

namespace aesim {

// What became of a fired event.
enum class Fate : std::uint8_t {
  Delivered,  // reached the receiver output intact
  Collided,   // lost in a collision the receiver detected and discarded
  Absorbed,   // fired while Ack was high (cycle fidelity): withdrawn before the receiver could see it;
              // a collision with the transaction in progress, counted and written as "collided"
  Ghost,      // lost in a collision the receiver did not detect: it output the OR of the addresses
  Dropped,    // lost for another reason (receiver FIFO full)
  Pending,    // still waiting for the bus when the run ended (arbitrated bus past saturation)
};
const char* to_string(Fate fate);

// Ground truth for one fired event (--truth).
struct TruthRecord {
  AddressEvent firing;  // firing.t is the fire time
  Fate fate = Fate::Delivered;
  double t_deliver = 0;  // when the receiver took it (Delivered only)
};

}  // namespace aesim
