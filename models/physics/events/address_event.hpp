#pragma once
#include <cstdint>

namespace aesim {

// A ghost is aesim's collision-corrupted event (p = 0 in aesim's own files). An OFF event is a
// recording of another tool's: polarity as contrast (light falling), as DVS cameras mean it.
enum EventFlags : std::uint8_t { kNormalEvent = 0, kGhostEvent = 1, kOffEvent = 2 };

// One address event: a pixel firing on its way to the receiver, or the event the receiver got.
struct AddressEvent {
  double t = 0;                 // s: firing time, or delivery time once delivered
  std::uint32_t x = 0, y = 0;   // global pixel coordinates
  std::uint32_t tile = 0;
  std::uint32_t bus_address = 0;
  std::uint8_t flags = kNormalEvent;
};

}  // namespace aesim
