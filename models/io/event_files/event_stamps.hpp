#pragma once
#include <cstdint>

#include "events/timestamps.hpp"

namespace aesim {

// An event's stamp in whole microseconds, as every event file carries it: whole receiver ticks
// first (timestamp_ticks), then microseconds. A tick of whole microseconds (1 us, the usual one)
// needs no second rounding; a finer tick rounds its tick count down to the microsecond.
// Whole means equal to its truncation (receiver.tick <= 1 s keeps it far inside the cast's range);
// no rounding call, as this runs once an event in every writer.
inline std::uint64_t stamp_us(double t, double tick) {
  const std::uint64_t ticks = timestamp_ticks(t, tick);
  const double us_per_tick = tick / 1e-6;
  const bool whole = us_per_tick >= 1 && us_per_tick == static_cast<double>(static_cast<std::uint64_t>(us_per_tick));
  return whole ? ticks * static_cast<std::uint64_t>(us_per_tick)
               : timestamp_ticks(static_cast<double>(ticks) * us_per_tick * 1e-6, 1e-6);
}

}  // namespace aesim
