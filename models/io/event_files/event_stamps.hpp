#pragma once
#include <cstdint>

#include "aesim/events/timestamps.hpp"

namespace aesim {

// An event's stamp in whole microseconds, as every event file carries it: whole receiver ticks
// first (timestamp_ticks), then microseconds. A tick of whole microseconds (1 us, the usual one)
// needs no second rounding; a finer tick rounds its tick count down to the microsecond.
// Whole means equal to its truncation (receiver.tick <= 1 s keeps it far inside the cast's range);
// no rounding call, as this runs once an event in every writer.
// With the tick's constants worked out once, for a writer's hot loop (a division and a check an
// event less).
class MicrosecondStamps {
 public:
  explicit MicrosecondStamps(double tick)
      : tick_(tick),
        us_per_tick_(tick / 1e-6),
        whole_(us_per_tick_ >= 1 && us_per_tick_ == static_cast<double>(static_cast<std::uint64_t>(us_per_tick_))),
        factor_(whole_ ? static_cast<std::uint64_t>(us_per_tick_) : 0) {}
  std::uint64_t operator()(double t) const {
    const std::uint64_t ticks = timestamp_ticks(t, tick_);
    return whole_ ? ticks * factor_ : timestamp_ticks(static_cast<double>(ticks) * us_per_tick_ * 1e-6, 1e-6);
  }

 private:
  double tick_;
  double us_per_tick_;
  bool whole_;
  std::uint64_t factor_;
};

}  // namespace aesim
