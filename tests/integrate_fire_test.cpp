// The pixel arithmetic against eq. 2 and hand-computed cases.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/pixel/integrate_fire.hpp"

namespace aesim {
namespace {

constexpr double kQ = 100e-15 * 1.0;  // c_int * dv_int

// The pixels of these tests share one sensor: no shot noise, reset time as given.
IntegrateFire::Sensor sensor(double t_reset) { return {t_reset, false}; }

IntegrateFire make(double current, double t_reset, double fraction = 0.0) {
  SplitMix64 rng(1);
  return IntegrateFire(sensor(t_reset), kQ, 0.0, current, fraction, rng);
}

std::vector<double> fire_until(IntegrateFire& p, double t_reset, double t_end) {
  IntegrateFire::ShotNoise rng;  // no shot noise: untouched
  std::vector<double> times;
  while (p.next_fire() <= t_end) {
    times.push_back(p.next_fire());
    p.fire(sensor(t_reset), rng);
  }
  return times;
}

TEST(IntegrateFire, ConstantCurrentFiresAtKTimesDtPlusResets) {
  for (double t_reset : {0.0, 1e-3}) {
    IntegrateFire p = make(1e-12, t_reset);  // dt_int = 100 ms
    const std::vector<double> times = fire_until(p, t_reset, 10.0);
    const std::size_t expected = t_reset == 0 ? 100 : 99;  // 100*0.1 + 99*1e-3 > 10
    ASSERT_EQ(times.size(), expected);
    for (std::size_t i = 0; i < times.size(); ++i) {
      const double k = static_cast<double>(i + 1);
      EXPECT_NEAR(times[i], k * 0.1 + (k - 1) * t_reset, 1e-13 * times[i]) << "firing " << k;
    }
  }
}

TEST(IntegrateFire, CurrentChangeMidIntegrationCarriesChargeOver) {
  // 1 pA for 0.25 s fires at 0.1, 0.2 and holds half the swing at 0.25; at 0.5 pA the other
  // half takes 0.1 s, so the next firing is at 0.35, then every 0.2 s.
  IntegrateFire p = make(1e-12, 0.0);
  const IntegrateFire::Sensor s = sensor(0.0);
  IntegrateFire::ShotNoise rng;
  EXPECT_NEAR(p.next_fire(), 0.1, 1e-15);
  p.fire(s, rng);
  EXPECT_NEAR(p.next_fire(), 0.2, 1e-15);
  p.fire(s, rng);
  EXPECT_NEAR(p.charge_at(s, 0.25), 0.5 * kQ, 1e-12 * kQ);
  p.set_current(s, 0.25, 0.5e-12);
  EXPECT_NEAR(p.next_fire(), 0.35, 1e-15);
  p.fire(s, rng);
  EXPECT_NEAR(p.next_fire(), 0.55, 1e-15);
}

TEST(IntegrateFire, CurrentChangeDuringResetStartsFromZeroAfterReset) {
  // Fires at 0.1 and 0.21; in reset until 0.22. A change at 0.215 applies from 0.22 with no
  // charge: 0.5 pA needs 0.2 s, so the next firing is at 0.42.
  IntegrateFire p = make(1e-12, 0.01);
  const IntegrateFire::Sensor s = sensor(0.01);
  IntegrateFire::ShotNoise rng;
  p.fire(s, rng);
  EXPECT_NEAR(p.next_fire(), 0.21, 1e-15);
  p.fire(s, rng);
  EXPECT_EQ(p.charge_at(s, 0.215), 0.0);
  p.set_current(s, 0.215, 0.5e-12);
  EXPECT_NEAR(p.next_fire(), 0.42, 1e-15);
}

TEST(IntegrateFire, InitialFractionShortensTheFirstIntegration) {
  IntegrateFire p = make(1e-12, 0.0, 0.25);
  EXPECT_NEAR(p.next_fire(), 0.075, 1e-15);
}

TEST(IntegrateFire, ZeroCurrentNeverFiresAndResumesWhenLit) {
  IntegrateFire p = make(0.0, 1e-3, 0.5);
  const IntegrateFire::Sensor s = sensor(1e-3);
  EXPECT_TRUE(std::isinf(p.next_fire()));
  EXPECT_EQ(p.charge_at(s, 1e9), 0.5 * kQ);
  p.set_current(s, 1e9, 1e-12);  // the held half swing fires 50 ms after the light comes on
  EXPECT_NEAR(p.next_fire(), 1e9 + 0.05, 1e-6);
}

TEST(IntegrateFire, TinyCurrentsGiveHugeFiniteTimesNotNaN) {
  for (double current : {1e-30, 1e-300, 5e-324}) {
    IntegrateFire p = make(current, 1e-6);
    const double t = p.next_fire();
    EXPECT_FALSE(std::isnan(t)) << current;
    EXPECT_GT(t, 1e15) << current;
    IntegrateFire::ShotNoise rng;
    p.fire(sensor(1e-6), rng);
    EXPECT_FALSE(std::isnan(p.next_fire())) << current;
  }
}

TEST(IntegrateFire, ShotNoiseIntegrationTimesFollowTheGammaLaw) {
  // N electrons collected at rate I/q: integration time ~ Gamma(N, q/I), mean N q/I, var N (q/I)^2.
  const double electrons = 1000;
  const double threshold = electrons * kElectronCharge;
  const double current = 1e-15;
  const double scale = kElectronCharge / current;
  IntegrateFire::ShotNoise noise{SplitMix64(42), threshold};
  const IntegrateFire::Sensor noisy{0.0, true};
  IntegrateFire p(noisy, threshold, 0.0, current, 0.0, noise.rng);
  const int n = 20000;
  double previous = 0, sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double dt = p.next_fire() - previous;
    previous = p.next_fire();
    p.fire(noisy, noise);
    sum += dt;
    sum2 += dt * dt;
  }
  const double mean = sum / n;
  const double var = (sum2 - n * mean * mean) / (n - 1);
  const double true_mean = electrons * scale;
  const double true_var = electrons * scale * scale;
  // Four standard errors: of the mean sqrt(var/n); of the variance var*sqrt(2/(n-1)) (Gamma
  // with N = 1000 is near-normal, excess kurtosis 6/N).
  EXPECT_NEAR(mean, true_mean, 4 * std::sqrt(true_var / n));
  EXPECT_NEAR(var, true_var, 4 * true_var * std::sqrt(2.0 / (n - 1) + 6.0 / electrons / n));
  // And it is noise: the relative spread is 1/sqrt(N), about 3 %.
  EXPECT_GT(std::sqrt(var) / mean, 0.025);
}

// The firings of IntegrateFire::Periodic up to `to`, passed through count_through and restart as
// FiringSchedule's still tiles do; the speculative first write of each call is dropped unless kept.
template <bool speculate>
std::vector<double> periodic_until(IntegrateFire::Periodic& p, double t_reset, double to) {
  std::vector<double> times;
  const auto emit = [&times](double t, bool kept) {
    if (kept) times.push_back(t);
  };
  using P = IntegrateFire::Periodic;
  while (!P::count_through<speculate>(p.first, p.period, p.cycles, to, emit)) {
    P::restart(p.first, p.period, p.cycles, p.integration, sensor(t_reset), emit);
  }
  return times;
}

TEST(IntegrateFire, PeriodicFormFiresAsFireDoes) {
  const double t_reset = 1e-3;
  for (const double fraction : {0.0, 0.4}) {
    IntegrateFire reference = make(1e-12, t_reset, fraction);
    IntegrateFire::Periodic fast = reference.periodic();
    IntegrateFire::Periodic speculating = reference.periodic();
    const std::vector<double> expected = fire_until(reference, t_reset, 10.0);
    std::vector<double> got, got_speculating;
    // Windows of every width from under a period to several, as a schedule's windows come.
    for (double to = 0.03; to <= 10.0; to += 0.037) {
      for (const double t : periodic_until<false>(fast, t_reset, to)) got.push_back(t);
      for (const double t : periodic_until<true>(speculating, t_reset, to)) got_speculating.push_back(t);
    }
    for (const double t : periodic_until<false>(fast, t_reset, 10.0)) got.push_back(t);
    for (const double t : periodic_until<true>(speculating, t_reset, 10.0)) got_speculating.push_back(t);
    EXPECT_EQ(got, expected);
    EXPECT_EQ(got_speculating, expected);
  }
}

// Every 2^30 firings the count restarts from a new anchor (before it could overflow): the firings
// go on a period apart, as eq. 2 gives them, in both forms.
TEST(IntegrateFire, PeriodicFormRestartsAt2To30CyclesWithoutAGap) {
  const double t_reset = 1e-6, integration = 1e-5, period = integration + t_reset;
  const std::uint32_t before_restart = (1u << 30) - 3;
  for (const bool speculate : {false, true}) {
    IntegrateFire::Periodic p{integration, period, integration, before_restart};
    const double t0 = integration + static_cast<double>(before_restart) * period;  // the next firing
    const double to = t0 + 7.5 * period;
    const std::vector<double> times =
        speculate ? periodic_until<true>(p, t_reset, to) : periodic_until<false>(p, t_reset, to);
    ASSERT_EQ(times.size(), 8u);
    for (std::size_t i = 0; i < times.size(); ++i) {
      EXPECT_NEAR(times[i], t0 + static_cast<double>(i) * period, 1e-12 * t0) << "firing " << i;
    }
    // Three firings before the restart, the 2^30th itself, then four from the new anchor.
    EXPECT_EQ(p.cycles, 4u);
    EXPECT_GT(p.first, times[3]);
    // Counted after the run: the ended cycles and the restart's firing, then the new ones, at or
    // before each firing's time and between them.
    for (std::size_t i = 0; i < times.size(); ++i) {
      for (const double t : {times[i], times[i] + 0.5 * period}) {
        const IntegrateFire::Periodic::Firings ended =
            IntegrateFire::Periodic::ended_by_restart(integration, period, 1u << 30, t);
        EXPECT_EQ(ended.all + p.cycles, before_restart + times.size());
        EXPECT_EQ(ended.within + IntegrateFire::Periodic::count_at_or_before(p.first, p.period, p.cycles, t),
                  before_restart + i + 1)
            << "firing " << i;
      }
    }
  }
}

// A periodic pixel's firings at or before a time, as the log's per-pixel counts take them, against
// counting the firings count_through gives one by one: at each firing's own time and beside it,
// where the quotient rounds either way, and where a period is below the anchor's resolution
// (many firings share a time, so the quotient is far off and only the search finds the count).
TEST(IntegrateFire, PeriodicCountAtOrBeforeIsTheFiringsCountedOneByOne) {
  using P = IntegrateFire::Periodic;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  struct Form {
    double first, period;
    std::uint32_t cycles;
  };
  std::vector<Form> forms = {{0.0, 1e-3, 1}, {0.0, 1e-3, 5000}, {0.1, 0.1, 3000}, {1e3, 1e-13, 4000},
                             {1e3, 1e-15, 20000}, {0.3, 1e-15, 2000}};
  for (int i = 0; i < 20; ++i) {
    forms.push_back({unit(rng) * 0.01, 1e-6 + unit(rng) * 1e-3, 1 + static_cast<std::uint32_t>(unit(rng) * 20000)});
  }
  for (const Form& f : forms) {
    SCOPED_TRACE(testing::Message() << "first " << f.first << " period " << f.period << " cycles " << f.cycles);
    // The firings count_through gives up to the last one's time (past it only firings that tie it).
    const double last = f.first + static_cast<double>(f.cycles - 1) * f.period;
    std::vector<double> times;
    std::uint32_t cycles = 0;
    ASSERT_TRUE(P::count_through<false>(f.first, f.period, cycles, last, [&times](double t, bool kept) {
      if (kept) times.push_back(t);
    }));
    ASSERT_GE(times.size(), f.cycles);
    times.resize(f.cycles);
    const auto counted = [&times](double t) {
      return static_cast<std::uint32_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    };
    std::vector<double> probes = {-1.0, 0.0, f.first, times.back(), std::nextafter(times.back(), 1e300), 1e300};
    for (std::size_t k = 0; k < times.size(); k += 1 + times.size() / 300) {
      probes.push_back(times[k]);
      probes.push_back(std::nextafter(times[k], -1e300));
      probes.push_back(std::nextafter(times[k], 1e300));
      probes.push_back(times[k] + 0.5 * f.period);
    }
    for (const double t : probes) EXPECT_EQ(P::count_at_or_before(f.first, f.period, f.cycles, t), counted(t)) << t;
  }
}

}  // namespace
}  // namespace aesim
