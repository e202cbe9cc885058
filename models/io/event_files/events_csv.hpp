#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "aesim/events/address_event.hpp"
#include "aesim/events/event_stream.hpp"

namespace aesim {

// Events CSV (docs/reference.md section 5): header t_us,x,y,tile,flags. t_us is the receiver timestamp in
// microseconds, printed with as many decimals as receiver.tick resolves (none at 1 us).
void write_events_csv(std::ostream& out, const std::vector<AddressEvent>& events, double tick);

// The same, as a run streams its events. When the tick is a whole number of the printed decimal
// unit (1 us, 10 ns, 1 ns, ...) timestamps are formatted from the integer tick count, which is
// exact and several times faster than formatting a double; other ticks print the double.
class EventsCsvWriter : public EventStream {
 public:
  EventsCsvWriter(std::ostream& out, double tick);
  ~EventsCsvWriter() override;
  void events(const AddressEvent* first, std::size_t count) override;
  void flush();

 private:
  std::ostream& out_;
  double tick_;
  int decimals_;
  std::uint64_t step_ = 0;   // ticks in units of 10^-decimals us, when whole; 0 otherwise
  std::uint64_t scale_ = 1;  // 10^decimals
  std::string buffer_;
};

// Reads such a file back; t is in seconds. Throws InputError on any malformed line.
std::vector<AddressEvent> read_events_csv(const std::string& path);
std::vector<AddressEvent> parse_events_csv(std::istream& in, const std::string& path);

}  // namespace aesim
