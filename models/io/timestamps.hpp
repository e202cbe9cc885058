#pragma once
#include <cmath>
#include <cstdint>

namespace aesim {

// The receiver's timestamp of an event at time t (s): whole ticks of `tick` seconds. A time
// within a millionth of a tick of an edge counts as on the edge, so that k * dt_int lands on
// the tick a user computes by hand despite binary rounding (0.1 s is 99999.99999999999 us).
inline std::uint64_t timestamp_ticks(double t, double tick) {
  const double ticks = t / tick;
  const double nearest = std::nearbyint(ticks);
  return static_cast<std::uint64_t>(std::fabs(ticks - nearest) < 1e-6 ? nearest : std::floor(ticks));
}

}  // namespace aesim
