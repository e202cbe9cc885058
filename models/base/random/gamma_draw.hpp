#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#include <boost/random/normal_distribution.hpp>

#include "aesim/random/splitmix64.hpp"

namespace aesim {

// Draws from Gamma(shape, 1) by Marsaglia and Tsang's method ("A simple method for generating
// gamma variables", ACM TOMS 26(3), 2000): exact (a rejection method on a normal and a uniform
// draw), accepting 98 % of first tries at shape 1 and nearly all at the thousands of electrons of
// a pixel's swing. Squeeze tests spare the logarithms: theirs (a tenth of draws get past it) and
// one that tightens as the shape grows (redraw() below), past which almost no draw of a pixel
// gets. Below shape 1 it draws at shape+1 and scales by U^(1/shape) (their section 6). The
// constants are worked out once per shape, so a pixel keeps its law beside its random stream;
// tests/gamma_draw_test.cpp checks draws against the exact distribution function. The normal
// draws are Boost.Random's ziggurat (128 layers, exact, one 64-bit draw nearly always).
class GammaDraw {
 public:
  GammaDraw() = default;
  explicit GammaDraw(double shape)
      : d_((shape < 1 ? shape + 1 : shape) - 1.0 / 3),
        c_(1 / std::sqrt(9 * d_)),
        k_(c_ * c_ / 12),
        small_(shape < 1 ? 1 / shape : 0) {}

  // One draw from rng. Inline, where a pixel's firing loop calls it: the common case, a first try
  // the ziggurat's rectangle and the added squeeze both accept (97 % of a pixel's draws), without
  // a call, so that the loop keeps its doubles in registers (a call, even one rarely taken, makes
  // the compiler keep them in memory: in a bare loop of draws at a pixel's shape, 5.6 ns a draw
  // with the whole method inline against 4.0). Anything else starts the draw again from the same
  // state out of line: the same values from the same stream either way.
  double operator()(SplitMix64& rng) const {
    double x;
    if (__builtin_expect(first_try(rng, x), 1)) return x;
    const Drawn again = redraw(rng);
    rng = again.rng;
    return again.value;
  }
  // The common case alone: true with the draw in `x` and rng past it, or false with rng untouched
  // (redraw() then makes the draw from it). For a loop that keeps even the rare call out of its
  // own body.
  bool first_try(SplitMix64& rng, double& x) const;

  // What redraw() returns: the draw, and the stream after it.
  struct Drawn {
    double value;
    SplitMix64 rng;
  };
  // The whole method from the stream's state `rng`: every try, every squeeze and the exact test.
  Drawn redraw(SplitMix64 rng) const;

 private:
  double d_ = 2.0 / 3, c_ = 1 / std::sqrt(6.0), k_ = 1.0 / 72, small_ = 0;
};

inline bool GammaDraw::first_try(SplitMix64& rng, double& draw) const {
  // The first try as redraw() makes it. Boost's ziggurat takes a 64-bit draw's low byte as its
  // layer (bits 1-7) and sign (bit 0: 1 is +), and its top 56 bits, bit 11 of the draw cleared,
  // as the fraction of the layer's width; tests/gamma_draw_test.cpp checks these draws against
  // Boost's own normal_distribution, so a Boost that changed them would fail there, not here.
  SplitMix64 next = rng;
  const std::uint64_t bits = next();
  const double* const layer_x = boost::random::detail::normal_table<double>::table_x;
  const auto layer = static_cast<unsigned>(bits & 0xFF) >> 1;
  const double fraction = static_cast<double>((bits & ~(std::uint64_t(1) << 11)) >> 8) * 0x1p-56;
  double x = fraction * layer_x[layer];
  if (!(x < layer_x[layer + 1]) || small_ != 0) return false;
  // The sign without a branch (it is a coin toss): x * -1 is -x exactly, as Boost's x * sign.
  std::uint64_t x_bits;
  std::memcpy(&x_bits, &x, sizeof x);
  x_bits ^= (~bits & 1) << 63;
  std::memcpy(&x, &x_bits, sizeof x);
  double v = 1 + c_ * x;
  if (!(v > 0)) return false;
  v = v * v * v;
  const double u = uniform01(next);
  const double x2 = x * x, x4 = x2 * x2;
  const double rest = 1 - std::fabs(c_ * x);
  if (!(rest > 0 && u * rest < rest - k_ * x4)) return false;
  draw = d_ * v;
  rng = next;
  return true;
}

}  // namespace aesim
