#pragma once
#include <iosfwd>
#include <vector>

#include <string>

#include "aesim/events/event_stream.hpp"

namespace aesim {

// Ground truth (--truth): one row per fired event in fire order:
//   x,y,tile,t_fire_us,fate,t_deliver_us,latency_us
// Times in microseconds with picosecond resolution; delivery time and latency are empty for
// events that were not delivered. Delivery time is when the receiver took the event (its latch
// edge at the cycle fidelity, its turn on an arbitrated bus, its firing on ALOHA and ideal buses).
void write_truth_csv(std::ostream& out, const std::vector<TruthRecord>& truth);

// The same, as a run streams its truth.
class TruthCsvWriter : public EventStream {
 public:
  explicit TruthCsvWriter(std::ostream& out);
  ~TruthCsvWriter() override;
  void events(const AddressEvent*, std::size_t) override {}
  void truth(const TruthRecord* first, std::size_t count) override;
  void flush();

 private:
  std::ostream& out_;
  std::string buffer_;
};

}  // namespace aesim
