#pragma once
#include <cmath>

#include "aesim/random/splitmix64.hpp"

namespace aesim {

// Draws from Gamma(shape, 1) by Marsaglia and Tsang's method ("A simple method for generating
// gamma variables", ACM TOMS 26(3), 2000): exact (a rejection method on a normal and a uniform
// draw), accepting 98 % of first tries at shape 1 and nearly all at the thousands of electrons of
// a pixel's swing. Squeeze tests spare the logarithms: theirs (a tenth of draws get past it) and
// one that tightens as the shape grows (gamma_draw.cpp), past which almost no draw of a pixel gets. Below shape 1 it draws at shape+1
// and scales by U^(1/shape) (their section 6). The constants are worked out once per shape, so a
// pixel keeps its law beside its random stream; tests/gamma_draw_test.cpp checks draws against
// the exact distribution function. The normal draws are Boost.Random's ziggurat (128 layers,
// exact, one 64-bit draw nearly always), inlined in the one out-of-line call a draw costs.
class GammaDraw {
 public:
  GammaDraw() = default;
  explicit GammaDraw(double shape)
      : d_((shape < 1 ? shape + 1 : shape) - 1.0 / 3),
        c_(1 / std::sqrt(9 * d_)),
        k_(c_ * c_ / 12),
        small_(shape < 1 ? 1 / shape : 0) {}

  // One draw from rng.
  double operator()(SplitMix64& rng) const;

 private:
  double d_ = 2.0 / 3, c_ = 1 / std::sqrt(6.0), k_ = 1.0 / 72, small_ = 0;
};

}  // namespace aesim
