#pragma once
#include <cmath>

#include <boost/random/normal_distribution.hpp>

#include "aesim/random/splitmix64.hpp"

namespace aesim {

// Draws from Gamma(shape, 1) by Marsaglia and Tsang's method ("A simple method for generating
// gamma variables", ACM TOMS 26(3), 2000): exact (a rejection method on a normal and a uniform
// draw), accepting 98 % of first tries at shape 1 and nearly all at the thousands of electrons of
// a pixel's swing. Squeeze tests spare the logarithms: theirs (a tenth of draws get past it) and
// one that tightens as the shape grows (operator() below), past which almost no draw of a pixel
// gets. Below shape 1 it draws at shape+1 and scales by U^(1/shape) (their section 6). The
// constants are worked out once per shape, so a pixel keeps its law beside its random stream;
// tests/gamma_draw_test.cpp checks draws against the exact distribution function. The normal
// draws are Boost.Random's ziggurat (128 layers, exact, one 64-bit draw nearly always), inline
// with the rest in the pixel's firing loop.
class GammaDraw {
 public:
  GammaDraw() = default;
  explicit GammaDraw(double shape)
      : d_((shape < 1 ? shape + 1 : shape) - 1.0 / 3),
        c_(1 / std::sqrt(9 * d_)),
        k_(c_ * c_ / 12),
        small_(shape < 1 ? 1 / shape : 0) {}

  // One draw from rng; inline, where a pixel's firing loop calls it (the call's own cost was a
  // few percent of a shot-noise run).
  double operator()(SplitMix64& rng) const;

 private:
  double d_ = 2.0 / 3, c_ = 1 / std::sqrt(6.0), k_ = 1.0 / 72, small_ = 0;
};

inline double GammaDraw::operator()(SplitMix64& rng) const {
  // The ziggurat keeps no spare draw between calls: a fresh distribution each time is two doubles.
  boost::random::normal_distribution<double> normal;
  for (;;) {
    double x, v;
    do {
      x = normal(rng);
      v = 1 + c_ * x;
    } while (v <= 0);
    v = v * v * v;
    const double u = uniform01(rng);
    const double x2 = x * x, x4 = x2 * x2;
    // The draw is accepted when log(u) < h(x) = x^2/2 + d(1 - v + log v). With y = c x,
    // h = 3d(-y^4/4 + y^5/5 - y^6/6 + ...) for |y| < 1; the terms alternate and shrink for y > 0
    // and all are negative for y < 0, each at most y^4/4 in size, so h >= -(3/4) d y^4 / (1 - |y|)
    // = -k x^4 / (1 - |y|), k = c^2 / 12 (d c^2 = 1/9), and since e^h >= 1 + h, u below
    // 1 - k x^4 / (1 - |y|) is accepted: at a pixel's thousands of electrons k is tiny and this
    // spares nearly every logarithm, where their squeeze (1 - 0.0331 x^4) spares nine in ten.
    const double rest = 1 - std::fabs(c_ * x);
    if ((rest > 0 && u * rest < rest - k_ * x4) || u < 1 - 0.0331 * x4 ||
        std::log(u) < 0.5 * x2 + d_ * (1 - v + std::log(v))) {
      return small_ > 0 ? d_ * v * std::pow(uniform01(rng), small_) : d_ * v;
    }
  }
}

}  // namespace aesim
