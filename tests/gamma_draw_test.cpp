// The shot-noise sampler against the exact gamma law: Kolmogorov-Smirnov distances of its draws
// to the regularised incomplete gamma function (Boost.Math, an implementation of its own), from
// below shape 1 (the boosted branch) to the hundreds of thousands of electrons of a real swing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/special_functions/gamma.hpp>
#include <boost/random/normal_distribution.hpp>

#include "aesim/random/gamma_draw.hpp"

namespace aesim {
namespace {

// sup |F_n(x) - F(x)| over the sorted sample.
double ks_distance(std::vector<double> x, double shape) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = boost::math::gamma_p(shape, x[i]);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  return d;
}

TEST(GammaDraw, DrawsFollowTheExactLawFromBelowOneToAPixelsSwing) {
  const int n = 100000;
  // At the 0.1 % level the KS distance of n draws from their own law stays under 1.95 / sqrt(n);
  // six shapes, so a correct sampler fails one of them with probability under 0.6 %.
  const double critical = 1.95 / std::sqrt(static_cast<double>(n));
  for (const double shape : {0.3, 1.0, 2.5, 10.0, 1000.0, 312000.0}) {
    SplitMix64 rng(static_cast<std::uint64_t>(shape * 1000) + 17);
    const GammaDraw draw(shape);
    std::vector<double> x(n);
    for (double& v : x) v = draw(rng);
    EXPECT_LT(ks_distance(x, shape), critical) << "shape " << shape;
    // And the law is not a neighbour's: a shape 1 % off is far outside at the large shapes.
    if (shape >= 1000) {
      EXPECT_GT(ks_distance(x, shape * 1.01), 5 * critical) << "shape " << shape;
    }
  }
}

// The squeeze GammaDraw adds accepts u below 1 - k x^4 / (1 - |c x|), k = c^2 / 12: it is
// only right if that never exceeds the acceptance probability exp(h(x)), h = x^2/2 + d(1 - v +
// log v), v = (1 + c x)^3. Checked on a fine grid over all |c x| < 1 (in long double) for shapes
// from the boosted branch to a pixel's swing, where a draw test could not see a bias this small.
TEST(GammaDraw, TheAddedSqueezeNeverAcceptsMoreThanTheExactTest) {
  for (const long double shape : {1.3L, 2.0L, 10.0L, 1000.0L, 312000.0L, 1e9L}) {
    const long double d = shape - 1.0L / 3, c = 1 / std::sqrt(9 * d), k = c * c / 12;
    const int steps = 200000;
    for (int i = 1; i < steps; ++i) {
      const long double y = -1 + 2.0L * i / steps;  // c x over (-1, 1)
      const long double x = y / c, v = (1 + y) * (1 + y) * (1 + y);
      const long double accept = std::exp(x * x / 2 + d * (1 - v + std::log(v)));
      const long double squeeze = 1 - k * x * x * x * x / (1 - std::fabs(y));
      ASSERT_LE(squeeze, accept * (1 + 1e-12L)) << "shape " << static_cast<double>(shape) << ", c x " << static_cast<double>(y);
    }
  }
}

// Marsaglia and Tsang's method as their paper gives it, on Boost's normal_distribution, without
// the squeezes: every GammaDraw draw, first tries written out inline and redraws alike, must be
// this one's to the bit, on the same stream (the squeezes only spare logarithms, and the inline
// first try must read a 64-bit draw as Boost's ziggurat does).
double textbook_gamma(double shape, SplitMix64& rng) {
  const double d = (shape < 1 ? shape + 1 : shape) - 1.0 / 3, c = 1 / std::sqrt(9 * d);
  boost::random::normal_distribution<double> normal;
  for (;;) {
    double x, v;
    do {
      x = normal(rng);
      v = 1 + c * x;
    } while (v <= 0);
    v = v * v * v;
    const double u = uniform01(rng);
    if (std::log(u) < 0.5 * x * x + d * (1 - v + std::log(v))) {
      return shape < 1 ? d * v * std::pow(uniform01(rng), 1 / shape) : d * v;
    }
  }
}

TEST(GammaDraw, DrawsAreTheTextbookMethodsOnBoostsNormalBitForBit) {
  for (const double shape : {0.3, 1.0, 2.5, 10.0, 1000.0, 624151.0}) {
    const GammaDraw draw(shape);
    SplitMix64 ours(static_cast<std::uint64_t>(shape * 7) + 3), theirs = ours;
    int first_tries = 0;
    for (int i = 0; i < 200000; ++i) {
      SplitMix64 probe = ours;
      double x;
      first_tries += draw.first_try(probe, x) ? 1 : 0;
      const double expected = textbook_gamma(shape, theirs);
      ASSERT_EQ(draw(ours), expected) << "shape " << shape << ", draw " << i;
    }
    // Both ways are taken. At a large shape the squeeze accepts nearly every try, so the first
    // try settles a draw when its point falls in the ziggurat's rectangle of its layer: with
    // probability the mean over the 128 layers of x[i+1] / x[i] (Boost's table), within five
    // binomial standard deviations. None below shape 1.
    if (shape >= 1000) {
      const double* const x = boost::random::detail::normal_table<double>::table_x;
      double p = 0;
      for (int layer = 0; layer < 128; ++layer) p += x[layer + 1] / x[layer] / 128;
      const double n = 200000, sd = std::sqrt(n * p * (1 - p));
      EXPECT_NEAR(first_tries, n * p, 5 * sd) << "shape " << shape << ", rectangle probability " << p;
    }
    if (shape < 1) {
      EXPECT_EQ(first_tries, 0);
    }
  }
}

// A first try that does not settle its draw leaves the stream where it was, and redraw() from
// there makes the draw operator() makes.
TEST(GammaDraw, AFirstTryThatFailsLeavesTheStreamUntouched) {
  const GammaDraw draw(1000.0);
  SplitMix64 rng(11);
  int failed = 0;
  for (int i = 0; i < 100000 && failed < 100; ++i) {
    const SplitMix64 before = rng;
    double x;
    if (draw.first_try(rng, x)) continue;
    ++failed;
    SplitMix64 untouched = before;
    EXPECT_EQ(rng(), untouched());
    SplitMix64 direct = before;
    const double expected = draw(direct);
    const GammaDraw::Drawn again = draw.redraw(before);
    EXPECT_EQ(again.value, expected);
    rng = again.rng;
    EXPECT_EQ(rng(), direct());
  }
  EXPECT_EQ(failed, 100);
}

TEST(GammaDraw, TheSameStreamGivesTheSameDraws) {
  const GammaDraw draw(4000.0);
  SplitMix64 a(9), b(9), c(10);
  for (int i = 0; i < 1000; ++i) {
    const double x = draw(a);
    EXPECT_EQ(x, draw(b));
    EXPECT_NE(x, draw(c));
  }
}

}  // namespace
}  // namespace aesim
