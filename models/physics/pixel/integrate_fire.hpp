#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "aesim/random/gamma_draw.hpp"
#include "aesim/random/splitmix64.hpp"

namespace aesim {

// Elementary charge, C: sets the electron count of a shot-noise integration.
inline constexpr double kElectronCharge = 1.602176634e-19;
inline constexpr double kNever = std::numeric_limits<double>::infinity();

// The arithmetic of one integrate-and-fire pixel (eq. 2: dt_int = c_int * dv_int / I), shared by
// every fidelity. Times are exact doubles in seconds; nothing is time-stepped.
//
// The pixel collects charge at its current I until it holds `target` coulombs, fires, spends
// t_reset in reset, and starts again from zero. Without shot noise the target is the pixel's
// threshold charge c_int*dv_int (with its mismatch). With shot noise each integration draws its
// target as q * Gamma(N, 1), N = threshold/q: the N-th arrival of a unit-rate Poisson process in
// collected charge, so a constant current gives Gamma(N, q/I) integration times and a current
// change mid-integration (a new frame) is still exact.
//
// With constant current the k-th firing after an anchor is computed in closed form from the
// anchor, so firing times do not accumulate rounding error over long runs.
//
// What all pixels of a sensor share (reset time, shot noise) is passed in, not stored, and so is
// what only shot noise needs (the pixel's threshold charge and random stream), so that a pixel's
// state is 52 bytes (56 with padding, which a derived class may fill): a megapixel array schedules
// in well under 100 bytes per pixel.
// When a pixel's next firing and its next change of light fall at the same time, the firing comes
// first: the charge reached threshold under the old light. Every rung orders the two by this.
inline bool fires_first(double t_fire, double t_light_change) { return t_fire <= t_light_change; }

class IntegrateFire {
 public:
  struct Sensor {
    double t_reset = 0;  // s
    bool shot_noise = false;
  };
  // With shot noise, what each new integration's target is drawn from: the pixel's threshold
  // charge (with mismatch), the law of its electron count and its own random stream. Untouched
  // without shot noise.
  struct ShotNoise {
    ShotNoise() = default;
    ShotNoise(SplitMix64 stream, double threshold_charge)
        : rng(stream), threshold(threshold_charge), electrons(threshold_charge / kElectronCharge) {}
    // The next integration's target: the one drawn ahead if there is one, else a fresh draw.
    // Either way the pixel's k-th integration gets its stream's k-th draw.
    double next_target() {
      if (!std::isnan(ahead)) {
        const double target = ahead;
        ahead = std::numeric_limits<double>::quiet_NaN();
        return target;
      }
      return kElectronCharge * electrons(rng);
    }
    SplitMix64 rng{0};
    double threshold = 0;  // C
    GammaDraw electrons;   // Gamma(threshold / q, 1)
    // fire_through_noisy() draws each target one integration before it is needed, and keeps the
    // one drawn ahead here between calls (NaN: none).
    double ahead = std::numeric_limits<double>::quiet_NaN();
  };

  IntegrateFire() = default;
  // Starts at time t0 with current `current` and `initial_fraction` of the swing already
  // collected (0 for pixel.initial=reset). `threshold` is this pixel's c_int * dv_int (with
  // mismatch); `rng` its shot-noise stream.
  IntegrateFire(const Sensor& sensor, double threshold, double t0, double current, double initial_fraction,
                SplitMix64& rng);

  // Time of the next firing, or kNever when the current is zero: one multiply-add from the
  // anchor (the branch keeps 0 * an overflowed period from making a NaN).
  double next_fire() const { return cycles_ == 0 ? first_ : first_ + static_cast<double>(cycles_) * period_; }
  // Consumes the firing at next_fire(): the pixel enters reset and starts a new integration.
  void fire(const Sensor& sensor, ShotNoise& noise) {
    if (sensor.shot_noise || cycles_ >= kMaxCycles) {
      start_new_integration(sensor, noise);
      anchored(sensor);
    } else {
      ++cycles_;
    }
  }
  // fire() at each firing up to and including time `to`, handing each firing's time to `emit`
  // first: the same times as next_fire() and fire() one at a time. fire_through() is for a pixel
  // without shot noise (its period stays, so the loop runs in registers), fire_through_noisy()
  // for one with.
  template <typename Emit>
  void fire_through_noisy(const Sensor& sensor, ShotNoise& noise, double to, Emit&& emit) {
    // start_new_integration() and anchored() written out: the same arithmetic, without the calls,
    // and what no firing in the loop reads (the charge at the anchor, the period) set once after.
    const double t_reset = sensor.t_reset, current = current_;
    double t = first_;
    if (!(t <= to)) return;
    double target = target_, anchor = anchor_t_;
    // Each integration's target is drawn one firing early, after the firing that needs it is
    // timed, so that a draw the first try does not settle can leave the loop for redraw() and come
    // back to the same place: a call in the loop, even one rarely taken, would have the compiler
    // keep the loop's doubles in memory. The same draws, in the same order.
    double next = noise.next_target();
    SplitMix64 rng = noise.rng;  // in registers: emit's stores would make the compiler reload it
    for (;;) {
      bool drawn = true;
      while (t <= to) {
        emit(t);
        anchor = t + t_reset;
        target = next;
        t = anchor + target / current;
        double electrons;
        if (__builtin_expect(!noise.electrons.first_try(rng, electrons), 0)) {
          drawn = false;
          break;
        }
        next = kElectronCharge * electrons;
      }
      if (drawn) break;
      const GammaDraw::Drawn again = noise.electrons.redraw(rng);
      rng = again.rng;
      next = kElectronCharge * again.value;
    }
    noise.rng = rng;
    noise.ahead = next;
    first_ = t;
    anchor_t_ = anchor;
    target_ = target;
    anchor_q_ = 0;
    period_ = target / current + t_reset;
  }

  template <typename Emit>
  void fire_through(const Sensor& sensor, ShotNoise& noise, double to, Emit&& emit) {
    while (!__builtin_expect(Periodic::count_through<false>(first_, period_, cycles_, to, emit), 1)) {
      // Past 2^30 cycles: re-anchored as fire() does.
      emit(next_fire(), true);
      fire(sensor, noise);
    }
  }

  // A pixel under light that never changes again and without shot noise, as the three numbers its
  // firings read and one more for every 2^30th: its state packed small, so that a tile of such
  // pixels can keep them in arrays of their own (a 2048x2048 array's windows read 20 bytes a pixel
  // instead of its 56-byte IntegrateFire). The same firing times as fire_through().
  struct Periodic {
    double first;        // the first firing after the anchor
    double period;       // s, with the reset
    double integration;  // s, threshold / current: the first firing after a re-anchor comes this long after its reset
    std::uint32_t cycles;

    // Emits the firings at first + k period up to `to`, counting them in `cycles`; false when it
    // stops at 2^30 cycles with a firing at or before `to` still to come. emit(t, kept): with
    // `speculate`, the next firing is handed over whether or not it is due, kept saying which (where
    // a window holds under two firings a pixel, whether a pixel fires in it is unpredictable, and
    // a mispredicted branch a pixel costs more than a write the receiver drops); every other
    // firing is kept.
    template <bool speculate, typename Emit>
    static bool count_through(double first, double period, std::uint32_t& cycles, double to, Emit&& emit) {
      std::uint32_t c = cycles;
      double t = c == 0 ? first : first + static_cast<double>(c) * period;
      if constexpr (speculate) {
        const bool due = t <= to && c < kMaxCycles;
        emit(t, due);
        c += due;
        t = c == 0 ? first : first + static_cast<double>(c) * period;
      }
      for (; t <= to && c < kMaxCycles; t = first + static_cast<double>(c) * period) {
        emit(t, true);
        ++c;
      }
      cycles = c;
      return !(t <= to);
    }
    // Of the firings count_through times at first + k period, k = 0 .. cycles - 1, how many fall
    // at or before `t`: from the quotient, then by bisection where rounding put the quotient off
    // by more than one (their times never decrease with k, rounding being monotonic).
    static std::uint32_t count_at_or_before(double first, double period, std::uint32_t cycles, double t) {
      const auto time = [first, period](std::uint32_t k) {
        return k == 0 ? first : first + static_cast<double>(k) * period;
      };
      if (cycles == 0 || !(first <= t)) return 0;
      if (time(cycles - 1) <= t) return cycles;
      // The last firing at or before t is in [lo, hi): time(lo) <= t < time(hi).
      std::uint32_t lo = 0, hi = cycles - 1;
      const double guess = std::floor((t - first) / period);
      if (guess > 0 && guess < static_cast<double>(hi)) {
        const auto k = static_cast<std::uint32_t>(guess);
        if (time(k) <= t) {
          lo = k;
          if (t < time(k + 1)) hi = k + 1;
        } else {
          hi = k;
        }
      }
      while (hi - lo > 1) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        (time(mid) <= t ? lo : hi) = mid;
      }
      return lo + 1;
    }
    // Of a run of firings that ended in restart(), after count_through stopped at `cycles`: the
    // firings in all (restart's own one more), and those at or before `t`.
    struct Firings {
      std::uint32_t all, within;
    };
    static Firings ended_by_restart(double first, double period, std::uint32_t cycles, double t) {
      const double restart = first + static_cast<double>(cycles) * period;
      return {cycles + 1, count_at_or_before(first, period, cycles, t) + (restart <= t ? 1u : 0u)};
    }
    // The firing at 2^30 cycles, then the state fire() leaves: anchored at its reset's end with no
    // charge.
    template <typename Emit>
    static void restart(double& first, double& period, std::uint32_t& cycles, double integration,
                        const Sensor& sensor, Emit&& emit) {
      const double t = first + static_cast<double>(cycles) * period;
      emit(t, true);
      first = (t + sensor.t_reset) + integration;
      period = integration + sensor.t_reset;
      cycles = 0;
    }
  };
  // This pixel as a Periodic: for one whose light never changes again, without shot noise.
  Periodic periodic() const { return {first_, period_, target_ / current_, cycles_}; }
  // The current changes at time t (last firing <= t <= next_fire()); collected charge carries over.
  void set_current(const Sensor& sensor, double t, double current);
  // Charge collected at time t (zero during reset); t within [last firing, next_fire()].
  double charge_at(const Sensor& sensor, double t) const;

 private:
  // Re-anchor before the cycle count could overflow (a pixel firing for 2^30 cycles).
  static constexpr std::uint32_t kMaxCycles = 1u << 30;

  double reset_end_of_last_cycle(const Sensor& sensor) const;
  // Re-anchors after the firing at next_fire() (each shot-noise integration has its own target).
  void start_new_integration(const Sensor& sensor, ShotNoise& noise);
  // The anchor, target or current changed: the first firing after the anchor and the period
  // from then on, the only divisions, once until the next change.
  void anchored(const Sensor& sensor) {
    if (!(current_ > 0)) {
      first_ = kNever;
      period_ = 0;
      return;
    }
    first_ = anchor_t_ + (target_ - anchor_q_) / current_;
    period_ = target_ / current_ + sensor.t_reset;
  }

  double target_ = 0;     // C, charge to collect in this integration (the threshold without shot noise)
  double current_ = 0;    // A
  double anchor_t_ = 0;   // integration started (or resumed) at this time...
  double anchor_q_ = 0;   // ...holding this charge
  // What every firing reads, side by side at the end, where a derived class's field joins them
  // in the padding: one cache line reached in most records.
  double first_ = kNever;  // the first firing after the anchor
  double period_ = 0;      // s, from one firing to the next at this current (with the reset)
  std::uint32_t cycles_ = 0;  // firings since the anchor (constant current, no shot noise)
};

}  // namespace aesim
