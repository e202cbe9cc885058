#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "events/address_event.hpp"

namespace aesim {

// Events CSV (SPEC section 5): header t_us,x,y,tile,flags. t_us is the receiver timestamp in
// microseconds, printed with as many decimals as receiver.tick resolves (none at 1 us).
void write_events_csv(std::ostream& out, const std::vector<AddressEvent>& events, double tick);

// Reads such a file back; t is in seconds. Throws InputError on any malformed line.
std::vector<AddressEvent> read_events_csv(const std::string& path);
std::vector<AddressEvent> parse_events_csv(std::istream& in, const std::string& path);

}  // namespace aesim
