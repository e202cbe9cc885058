// Whole-array runs against docs/reference.md section 1: eq. 2 in closed form, frame boundaries, mismatch,
// zero and vanishing light.
#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/event_files/event_stamps.hpp"
#include "aesim/events/timestamps.hpp"
#include "aesim/random/splitmix64.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

using testing::exact_sensor;
using testing::make_image;
using testing::make_scene;

// Firing times of every pixel, indexed y * cols + x.
std::map<std::size_t, std::vector<double>> times_by_pixel(const SimulationResult& r, int cols) {
  std::map<std::size_t, std::vector<double>> out;
  for (const AddressEvent& e : r.log.events()) out[std::size_t(e.y) * cols + e.x].push_back(e.t);
  return out;
}

void expect_closed_form(const SensorConfig& c, const Image& img) {
  const Photocurrents photocurrents(make_scene({img}), c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  const auto times = times_by_pixel(r, c.array.cols);
  const double q = c.pixel.c_int * c.pixel.dv_int;
  std::uint64_t total = 0;
  for (int y = 0; y < c.array.rows; ++y) {
    for (int x = 0; x < c.array.cols; ++x) {
      const double current = c.pixel.i_dark + c.pixel.i_max * img.at(x, y);
      std::vector<double> expected;
      if (current > 0) {
        const double dt = q / current;
        for (double k = 1;; ++k) {
          const double t = k * dt + (k - 1) * c.pixel.t_reset;
          if (t > c.sim.duration) break;
          expected.push_back(t);
        }
      }
      const auto it = times.find(std::size_t(y) * c.array.cols + x);
      const std::vector<double> got = it == times.end() ? std::vector<double>{} : it->second;
      ASSERT_EQ(got.size(), expected.size()) << "pixel " << x << "," << y;
      for (std::size_t k = 0; k < got.size(); ++k) {
        EXPECT_NEAR(got[k], expected[k], 1e-13 * expected[k]) << "pixel " << x << "," << y << " firing " << k + 1;
      }
      total += expected.size();
    }
  }
  EXPECT_EQ(r.log.totals().fired, total);
  EXPECT_EQ(r.log.totals().delivered, total);
  EXPECT_GT(total, 0u);
}

TEST(ClosedForm, UniformSceneEveryPixelEveryFiring) {
  for (double t_reset : {0.0, 2e-3}) {
    SensorConfig c = exact_sensor(16, 16, 8);
    c.pixel.t_reset = t_reset;
    c.sim.duration = 3.05;
    expect_closed_form(c, make_image(16, 16, [](int, int) { return 0.8; }));
  }
}

TEST(ClosedForm, GradientSceneEveryPixelEveryFiring) {
  for (double t_reset : {0.0, 5e-3}) {
    SensorConfig c = exact_sensor(12, 20, 4);
    c.pixel.t_reset = t_reset;
    c.pixel.i_dark = 1e-15;
    c.sim.duration = 2.0;
    expect_closed_form(c, make_image(20, 12, [](int x, int y) { return (x + 20 * y) / 239.0; }));
  }
}

std::vector<double> single_pixel_run(double t_reset, double frame_period) {
  SensorConfig c = exact_sensor(1, 1, 1);
  c.pixel.t_reset = t_reset;
  c.sim.duration = 1.0;
  const Scene scene = make_scene({make_image(1, 1, [](int, int) { return 1.0; }),
                                  make_image(1, 1, [](int, int) { return 0.5; })},
                                 frame_period);
  const Photocurrents photocurrents(scene, c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  std::vector<double> times;
  for (const AddressEvent& e : r.log.events()) times.push_back(e.t);
  return times;
}

void expect_times(const std::vector<double>& got, const std::vector<double>& expected) {
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-12) << "firing " << i + 1;
}

TEST(ClosedForm, FrameBoundaryCarriesChargeOver) {
  // 1 pA (dt 0.1 s) until 0.25 s, then 0.5 pA (dt 0.2 s), last frame held. Half the swing is
  // held at the boundary, so the next firing comes 0.1 s later at 0.35.
  expect_times(single_pixel_run(0.0, 0.25), {0.1, 0.2, 0.35, 0.55, 0.75, 0.95});
  // With 10 ms reset: 0.1, 0.21, reset ends 0.22, 0.03 s of charge (3e-14 C) at the boundary,
  // the remaining 7e-14 C at 0.5 pA takes 0.14 s: 0.39, then every 0.21 s.
  expect_times(single_pixel_run(0.01, 0.25), {0.1, 0.21, 0.39, 0.6, 0.81});
  // A boundary during the reset (0.215 within 0.21..0.22): integration restarts at 0.22 from zero.
  expect_times(single_pixel_run(0.01, 0.215), {0.1, 0.21, 0.42, 0.63, 0.84});
}

TEST(ClosedForm, LoopedSequenceRepeats) {
  // Frames alternate 1 pA / dark every 0.33 s. The pixel fires at 0.1, 0.2, 0.3, holds 0.03 s
  // worth of charge through the dark frame, so needs only 0.07 s after 0.66: 0.73, 0.83, 0.93;
  // at 0.99 it holds 0.06 s worth, and the light returns at 1.32, after the run.
  SensorConfig c = exact_sensor(1, 1, 1);
  c.sim.duration = 1.25;
  const Scene scene = make_scene({make_image(1, 1, [](int, int) { return 1.0; }),
                                  make_image(1, 1, [](int, int) { return 0.0; })},
                                 0.33, true);
  const Photocurrents photocurrents(scene, c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  std::vector<double> times;
  for (const AddressEvent& e : r.log.events()) times.push_back(e.t);
  expect_times(times, {0.1, 0.2, 0.3, 0.73, 0.83, 0.93});
}

TEST(Light, StillSceneCurrentsAreWorkedOutAsASequencesAreTabulated) {
  // A still scene's currents are computed when asked, a sequence's tabulated up front: the same
  // pixel response either way, with the linear response and with a measured period table (whose
  // interpolation is where a difference would show).
  SensorConfig c = exact_sensor(8, 8, 8);
  c.pixel.i_dark = 3e-15;
  const Image img = make_image(8, 8, [](int x, int y) { return (x * 8 + y) / 63.0 * 1.7; });
  const Image dark = make_image(8, 8, [](int, int) { return 0.0; });
  for (const bool table : {false, true}) {
    if (table) c.pixel.transfer = TransferCurve{{1e-15, 1e-13, 1e-11}, {110.0, 1.3, 0.011}, 0, -1};
    const Photocurrents still(make_scene({img}), c.pixel);
    const Photocurrents sequence(make_scene({img, dark}, 0.5, false), c.pixel);
    ASSERT_EQ(still.frames(), 1u);
    for (std::size_t i = 0; i < 64; ++i) {
      const double expected = c.pixel.integrating_current(img.pixels[i]);
      EXPECT_EQ(still.current(0, i), expected) << "pixel " << i << (table ? " with the table" : "");
      EXPECT_EQ(still.current(7, i), expected) << "a still scene has no later frame";
      EXPECT_EQ(sequence.current(0, i), expected);
      EXPECT_EQ(sequence.current(1, i), c.pixel.integrating_current(0.0));
      EXPECT_EQ(still.next_change(0, i), Photocurrents::kNoChange);
    }
    EXPECT_EQ(still.scene().frames.front().pixels, img.pixels);
  }
}

TEST(Mismatch, SpreadOfPeriodsMatchesTheParameter) {
  SensorConfig c = exact_sensor(64, 64, 32);
  c.pixel.mismatch = 0.05;
  c.sim.duration = 0.25;  // two firings per pixel at 1 pA: 0.1 * (1 +- 0.05 * 4.5 sigma)
  const Photocurrents photocurrents(make_scene({make_image(64, 64, [](int, int) { return 1.0; })}), c.pixel);
  const auto times = times_by_pixel(simulate(c.resolved(), photocurrents), 64);
  ASSERT_EQ(times.size(), 4096u);
  double sum = 0, sum2 = 0;
  for (const auto& [pixel, t] : times) {
    ASSERT_GE(t.size(), 2u);
    const double relative_period = (t[1] - t[0]) / 0.1;
    sum += relative_period;
    sum2 += relative_period * relative_period;
  }
  const double n = 4096;
  const double mean = sum / n;
  const double sd = std::sqrt((sum2 - n * mean * mean) / (n - 1));
  // Four standard errors: of the mean 0.05/sqrt(n), of the standard deviation 0.05/sqrt(2n).
  EXPECT_NEAR(mean, 1.0, 4 * 0.05 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.05, 4 * 0.05 / std::sqrt(2 * n));
}

TEST(Light, ZeroCurrentNeverFiresAndTerminates) {
  SensorConfig c = exact_sensor(32, 32, 16);
  c.sim.duration = 1e6;
  const Photocurrents photocurrents(make_scene({make_image(32, 32, [](int, int) { return 0.0; })}), c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  EXPECT_EQ(r.log.totals().fired, 0u);
  EXPECT_TRUE(r.log.events().empty());
}

TEST(Light, VanishingCurrentsDoNotOverflowSimulatedTime) {
  // 1.25e-19 A fires every 8e5 s, near the end of the longest allowed run; 1.25e-30 A never
  // within it. Neither may overflow SystemC's 64-bit picosecond clock.
  SensorConfig c = exact_sensor(1, 2, 1);
  c.pixel.i_max = 1.25e-19;
  c.sim.duration = 1e6;
  const Photocurrents photocurrents(make_scene({make_image(2, 1, [](int x, int) { return x == 0 ? 1.0 : 1e-11; })}),
                                    c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  ASSERT_EQ(r.log.events().size(), 1u);
  EXPECT_EQ(r.log.events()[0].x, 0u);
  EXPECT_NEAR(r.log.events()[0].t, 8e5, 1e-6);
}

TEST(Seeds, SameSeedSameEventsOtherSeedOtherEvents) {
  SensorConfig c = exact_sensor(16, 16, 8);
  c.pixel.mismatch = 0.02;
  c.pixel.initial = InitialState::Random;
  c.pixel.shot_noise = true;
  const Photocurrents photocurrents(make_scene({make_image(16, 16, [](int x, int) { return x / 15.0; })}), c.pixel);
  auto run = [&](std::uint64_t seed) {
    c.sim.seed = seed;
    const SimulationResult r = simulate(c.resolved(), photocurrents);
    std::vector<std::pair<double, std::uint32_t>> v;
    for (const AddressEvent& e : r.log.events()) v.emplace_back(e.t, e.y * 16 + e.x);
    return v;
  };
  EXPECT_EQ(run(7), run(7));
  EXPECT_NE(run(7), run(8));
}

// timestamp_ticks rounds without the library (it runs once an event in the writers); the library's
// nearbyint and floor are the reference, on hand-picked edges and on random times over the range.
TEST(Timestamps, TicksEqualTheLibrarysRoundingEverywhere) {
  auto reference = [](double t, double tick) {
    const double ticks = t / tick;
    const double nearest = std::nearbyint(ticks);
    return static_cast<std::uint64_t>(std::fabs(ticks - nearest) < 1e-6 ? nearest : std::floor(ticks));
  };
  const double two52 = 4503599627370496.0;
  std::vector<std::pair<double, double>> cases = {
      {0.0, 1e-6}, {-0.0, 1e-6}, {0.1, 1e-6}, {0.3, 1e-6}, {2.5e-6, 1e-6}, {3.5e-6, 1e-6}, {0.9999999e-6, 1e-6},
      {1.0000001e-6, 1e-6}, {two52 - 0.5, 1.0}, {two52 - 1.5, 1.0}, {two52, 1.0}, {two52 + 2, 1.0},
      {9.1e18, 1.0}, {1e6, 1e-12}, {123.456789, 1e-9}};
  for (int k = 1; k <= 1000; ++k) cases.push_back({k * 0.1, 1e-6});  // 0.1 s is 99999.99999999999 us
  SplitMix64 rng(7);
  for (int i = 0; i < 100000; ++i) {
    const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    cases.push_back({u * std::pow(10.0, static_cast<double>(rng() % 13)), 1e-6});
  }
  for (const auto& [t, tick] : cases) EXPECT_EQ(timestamp_ticks(t, tick), reference(t, tick)) << t << " s at " << tick;
}

// The writers' stamps take a product by the tick's reciprocal where it gives the division's count:
// against timestamp_ticks itself on times within a few units in the last place of each count's
// step (a count just past k - 1e-6 ticks), of whole counts, on random times over the range, past
// 2^51 ticks, and on times it refuses.
TEST(Timestamps, TheWritersStampsCountAsTheDivisionDoes) {
  SplitMix64 rng(3);
  for (const double tick : {1e-6, 2e-6, 1e-5, 1e-7, 2.5e-7, 20e-9, 1e-6 / 3, 1.0}) {
    const MicrosecondStamps stamps(tick);
    std::vector<double> times = {0.0, -0.0, tick, 1e-6 * tick, 0x1p52 * tick, 0x1p51 * tick, 9e18 * tick};
    for (int i = 0; i < 20000; ++i) {
      const double k = std::floor(std::pow(10.0, static_cast<double>(rng() % 15)) * static_cast<double>(rng() >> 11) * 0x1.0p-53) + 1;
      for (const double q : {k - 1e-6, k, k + 1e-6}) {
        double t = q * tick;
        for (int j = 0; j < 6; ++j) t = std::nextafter(t, 0.0);
        for (int j = 0; j < 12; ++j, t = std::nextafter(t, 1e300)) times.push_back(t);
      }
      times.push_back(static_cast<double>(rng() >> 11) * 0x1.0p-53 * std::pow(10.0, static_cast<double>(rng() % 13)));
    }
    for (const double t : times) {
      std::uint64_t want = 0;
      try {
        want = timestamp_ticks(t, tick);
      } catch (const std::overflow_error&) {
        EXPECT_THROW(stamps.ticks_of(t), std::overflow_error) << t << " s at " << tick;
        continue;
      }
      ASSERT_EQ(stamps.ticks_of(t), want) << t << " s at " << tick;
    }
    for (const double t : {-1e-9, std::nan(""), 1e19 * tick}) {
      EXPECT_THROW(stamps.ticks_of(t), std::overflow_error) << t;
    }
  }
}

}  // namespace
}  // namespace aesim
