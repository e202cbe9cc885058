#pragma once
#include <cmath>
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
        per_tick_(1 / tick),
        us_per_tick_(tick / 1e-6),
        whole_(us_per_tick_ >= 1 && us_per_tick_ == static_cast<double>(static_cast<std::uint64_t>(us_per_tick_))),
        factor_(whole_ ? static_cast<std::uint64_t>(us_per_tick_) : 0) {}
  std::uint64_t operator()(double t) const {
    const std::uint64_t ticks = ticks_of(t);
    return whole_ ? ticks * factor_ : timestamp_ticks(static_cast<double>(ticks) * us_per_tick_ * 1e-6, 1e-6);
  }
  // timestamp_ticks(t, tick), with a product by the tick's reciprocal in place of the division
  // wherever the two give the same (a division was a quarter of the .npy writer's time). The
  // product m is within 3 units in the last place of the quotient q: 1/tick, the product and the
  // quotient are each rounded once. The count is q's whole part, or the whole number just above
  // q when q falls less than 1e-6 below it, so it steps only where q crosses k - 1e-6 for a whole
  // k; m gives the same count unless such a step lies between them, and a step lies within m's
  // rounding of m only where m lies that close to one. There, past 2^51 (where a unit in the last
  // place nears a tick), and for times timestamp_ticks refuses, the division decides.
  std::uint64_t ticks_of(double t) const {
    constexpr double kWhole = 4503599627370496.0;  // 2^52
    const double m = t * per_tick_;
    const double nearest = (m + kWhole) - kWhole;
    const double off = std::fabs(m - nearest);
    // One test for the rare cases, so that the common one runs without a branch; and m < 2^51
    // converts through a signed integer, which x86-64 does in one instruction (an unsigned
    // conversion tests for 2^63 first).
    const bool plain = (m >= 0) & (m < kWhole / 2) & (std::fabs(off - 1e-6) > m * 0x1p-50 + 1e-20);
    if (__builtin_expect(!plain, 0)) return timestamp_ticks(t, tick_);
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(off < 1e-6 ? nearest : m));
  }

 private:
  double tick_;
  double per_tick_;
  double us_per_tick_;
  bool whole_;
  std::uint64_t factor_;
};

// Stamps another tool kept as floats (or decimal text) in a unit its file does not name: seconds
// when any has a fraction (what Python keeps of seconds), microseconds when every one is whole (a
// camera's stamps kept as floats). The one rule every reader of such stamps follows (a CSV's time
// column, a .npy's float field, an HDF5 float dataset): see() each, then convert, and say which.
struct UnnamedStampUnit {
  bool seconds = false;
  void see(double stamp) { seconds = seconds || stamp != std::floor(stamp); }
  std::int64_t microseconds(double stamp) const { return std::llround(seconds ? stamp * 1e6 : stamp); }
  const char* words() const {
    return seconds ? "seconds, as its stamps have fractions" : "microseconds, as its stamps are whole numbers";
  }
};

}  // namespace aesim
