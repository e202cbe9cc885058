#pragma once
#include <string>
#include <vector>

#include "events/address_event.hpp"

namespace aesim {

// Events read back from an AEDAT 2.0 or CSV file written by aesim, with the array size they
// belong to (from the AEDAT header's sensor parameters, or the largest coordinates in a CSV).
struct EventRecording {
  std::vector<AddressEvent> events;  // t in seconds
  int width = 0, height = 0, tiles = 0;
};

EventRecording load_events(const std::string& path);

// The same from a file's bytes; `label` names it in messages.
enum class EventFormat { Aedat2, Csv };
EventRecording decode_events(const std::string& data, const std::string& label, EventFormat format);

}  // namespace aesim
