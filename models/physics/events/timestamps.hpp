#pragma once
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace aesim {

// The receiver's timestamp of an event at time t (s): whole ticks of `tick` seconds. A time
// within a millionth of a tick of an edge counts as on the edge, so that k * dt_int lands on
// the tick a user computes by hand despite binary rounding (0.1 s is 99999.99999999999 us).
// The configuration's ranges (tick >= 1 ps, runs <= 1e6 s) keep the count below 2^63; the check
// makes an overflow an error instead of undefined behaviour.
//
// Written for the writers' hot loops: for 0 <= x < 2^52, (x + 2^52) - 2^52 is std::nearbyint(x)
// (round to nearest, ties to even, as IEEE addition rounds), and above 2^52 every double is whole;
// the cast truncates, which for x >= 0 is std::floor. Both are library calls on a baseline x86-64.
inline std::uint64_t timestamp_ticks(double t, double tick) {
  constexpr double kWhole = 4503599627370496.0;  // 2^52
  const double ticks = t / tick;
  if (!(ticks >= 0 && ticks < 9.2e18)) throw std::overflow_error("timestamp out of the 64-bit tick range");
  const double nearest = ticks < kWhole ? (ticks + kWhole) - kWhole : ticks;
  return static_cast<std::uint64_t>(std::fabs(ticks - nearest) < 1e-6 ? nearest : ticks);
}

}  // namespace aesim
