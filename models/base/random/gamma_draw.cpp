#include "aesim/random/gamma_draw.hpp"

namespace aesim {

// Out of line and cold: operator() falls back to it for about 3 draws in 100 at a pixel's shape
// (those outside the ziggurat's rectangles, which hold 97.2 % of its points).
[[gnu::noinline, gnu::cold]] GammaDraw::Drawn GammaDraw::redraw(SplitMix64 rng) const {
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
      const double value = small_ > 0 ? d_ * v * std::pow(uniform01(rng), small_) : d_ * v;
      return {value, rng};
    }
  }
}

}  // namespace aesim
