#pragma once
#include <cstdint>
#include <functional>

#include "aesim/array/address_map.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/receiver/beat_decoder.hpp"

namespace aesim {

// The consumer of a receiver's event stream, one rising clock edge at a time: a beat with valid
// and ready both high before the edge is taken, decoded (BeatDecoder) into the log. `ready`
// decides, per edge, whether the consumer accepts in the next cycle (always, by default). Shared by the SystemC sink (receiver/event_sink) and the reference receiver's clock
// domain (receiver/reference_clock_domain), so both take the same beats.
class StreamConsumer {
 public:
  StreamConsumer(std::uint32_t tile, const AddressMap& map, double tick, int ts_width, EventLog& log)
      : decoder_(tile, map, tick, ts_width), log_(log) {}

  void set_ready_pattern(std::function<bool(std::uint64_t cycle)> ready) { ready_ = std::move(ready); }
  // A rising edge, with the values the wires held before it; returns ready for the next cycle.
  bool edge(bool valid, bool ready, std::uint64_t ts, std::uint32_t addr, bool flags) {
    if (valid && ready) take(ts, addr, flags);
    ++cycle_;
    return ready_ ? ready_(cycle_) : true;
  }

 private:
  void take(std::uint64_t ts, std::uint32_t addr, bool flags) { log_.output(decoder_.decode(ts, addr, flags)); }

  BeatDecoder decoder_;
  EventLog& log_;
  std::function<bool(std::uint64_t)> ready_;
  std::uint64_t cycle_ = 0;
};

}  // namespace aesim
