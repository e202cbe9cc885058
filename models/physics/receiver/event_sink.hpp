#pragma once
#include <cstdint>
#include <functional>
#include <systemc>

#include "array/address_map.hpp"
#include "events/event_log.hpp"
#include "receiver/receiver_signals.hpp"

namespace aesim {

// Reads a receiver's event stream: at each rising edge, a beat with valid and ready both high is
// taken. The timestamp is unwrapped (the counter wraps at 2^ts_width) and turned into seconds
// with the receiver's tick; the address into a pixel of the tile. `ready` decides, per edge,
// whether the sink accepts in the next cycle (always, by default).
class EventSink : public sc_core::sc_module {
 public:
  EventSink(const sc_core::sc_module_name& name, ReceiverSignals& s, std::uint32_t tile, const AddressMap& map,
            double tick, int ts_width, EventLog& log);
  SC_HAS_PROCESS(EventSink);

  void set_ready_pattern(std::function<bool(std::uint64_t cycle)> ready) { ready_ = std::move(ready); }

 private:
  void on_clock();

  ReceiverSignals& s_;
  std::uint32_t tile_;
  const AddressMap& map_;
  double tick_;
  std::uint64_t ts_modulus_;
  EventLog& log_;
  std::function<bool(std::uint64_t)> ready_;
  std::uint64_t cycle_ = 0;
  std::uint64_t last_ts_ = 0, wraps_ = 0;
};

}  // namespace aesim
