#pragma once
#include <cmath>
#include <cstdint>

#include "events/timestamps.hpp"

namespace aesim {

// An event's stamp in whole microseconds, as every event file carries it: whole receiver ticks
// first (timestamp_ticks), then microseconds. A tick of whole microseconds (1 us, the usual one)
// needs no second rounding; a finer tick rounds its tick count down to the microsecond.
inline std::uint64_t stamp_us(double t, double tick) {
  const std::uint64_t ticks = timestamp_ticks(t, tick);
  const double us_per_tick = tick / 1e-6;
  const double whole = std::nearbyint(us_per_tick);
  return whole >= 1 && us_per_tick == whole ? ticks * static_cast<std::uint64_t>(whole)
                                            : timestamp_ticks(static_cast<double>(ticks) * us_per_tick * 1e-6, 1e-6);
}

}  // namespace aesim
