// A tile's firings in order from its schedule: a still tile makes them a window at a time
// (FiringWindow) instead of through the calendar queue. The two must give the same firings in
// the same order whatever the callers ask for at a time, ties (pixels firing at the same instant)
// in bus-address order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <random>

#include "aesim/array/address_map.hpp"
#include "aesim/array/firing_schedule.hpp"
#include "support/scenes.hpp"

namespace aesim {
namespace {

using testing::exact_sensor;
using testing::make_image;
using testing::make_scene;

// Everything the schedule gives, asked for in batches of 1..`most` firings up to times that move
// on by random steps and now and then go back to the last firing's time (ties at the edge).
std::vector<AddressEvent> pull(FiringSchedule& s, double t_end, std::size_t most, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<AddressEvent> all, batch(most);
  double until = 0;
  for (;;) {
    const std::size_t n = s.fill(batch.data(), 1 + rng() % most, until);
    // Never a firing after the time asked up to, whatever the windows made.
    for (std::size_t i = 0; i < n; ++i) EXPECT_LE(batch[i].t, until);
    all.insert(all.end(), batch.begin(), batch.begin() + static_cast<std::ptrdiff_t>(n));
    if (n == 0) {
      if (until >= t_end) break;
      until = std::min(t_end, until + t_end * 0.07 * static_cast<double>(rng() % 100) / 100);
    } else if (rng() % 4 == 0) {
      until = all.back().t;
    }
  }
  return all;
}

void expect_same(const std::vector<AddressEvent>& a, const std::vector<AddressEvent>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].t, b[i].t) << i;
    ASSERT_EQ(a[i].bus_address, b[i].bus_address) << i;
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].tile, b[i].tile) << i;
    ASSERT_EQ(a[i].flags, b[i].flags) << i;
  }
}

struct Case {
  const char* name;
  SensorConfig config;
  Scene scene;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  // Identical pixels from reset under the same light: every pixel of the tile fires at the same
  // instants, so every firing ties with the tile's others.
  SensorConfig same = exact_sensor(40, 40, 16);
  same.sim.duration = 2.0;
  out.push_back({"ties", same, make_scene({make_image(40, 40, [](int, int) { return 0.7; })})});
  // Mismatch, random start, dark current and reset time, light from dark to 50x the dimmest lit
  // pixel, some pixels dark: periods over a wide range, a tile's windows set by its brightest.
  SensorConfig spread = exact_sensor(40, 40, 16);
  spread.pixel.mismatch = 0.05;
  spread.pixel.initial = InitialState::Random;
  spread.pixel.i_max = 20e-12;
  spread.pixel.i_dark = 1e-15;
  spread.pixel.t_reset = 1e-4;
  spread.sim.duration = 2.0;
  out.push_back({"spread", spread, make_scene({make_image(40, 40, [](int x, int y) {
                   return (x + y) % 7 == 0 ? 0.0 : (x == 20 && y == 3 ? 1.0 : 0.02 * (1 + (x * 3 + y) % 50));
                 })})});
  // The same with shot noise: each integration draws its electron count, so no two periods of a
  // pixel are alike, and the windows draw them in the calendar's order, pixel by pixel.
  SensorConfig noisy = spread;
  noisy.pixel.shot_noise = true;
  out.push_back({"shot noise", noisy, out.back().scene});
  // A bar sweeping the spread light, ten frames a second: each window ends at a change of light,
  // a pixel's charge carries over it. Held after the last frame, then looped; then looped with
  // shot noise.
  std::vector<Image> frames;
  for (int k = 0; k < 6; ++k) {
    frames.push_back(make_image(40, 40, [k](int x, int y) {
      if (std::abs(x - 7 * k) < 4) return 1.0;
      return (x + y) % 7 == 0 ? 0.0 : 0.02 * (1 + (x * 3 + y + k) % 50);
    }));
  }
  out.push_back({"moving, held", spread, make_scene(frames, 0.1)});
  out.push_back({"moving, looped", spread, make_scene(frames, 0.1, true)});
  out.push_back({"moving, looped, shot noise", noisy, make_scene(frames, 0.1, true)});
  return out;
}

TEST(FiringSchedule, WindowsGiveTheCalendarsFiringsInTheSameOrder) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Photocurrents photocurrents(c.scene, c.config.pixel);
    const AddressMap map(c.config.array);
    // Tile 2 is a partial tile at the array's right edge (40 = 16 + 16 + 8).
    for (const std::uint32_t tile : {0u, 2u, 4u}) {
      FiringSchedule windows(c.config.pixel, c.config.sim, photocurrents, map, tile);
      FiringSchedule calendar(c.config.pixel, c.config.sim, photocurrents, map, tile, false);
      ASSERT_TRUE(windows.windowed());
      ASSERT_FALSE(calendar.windowed());
      const double t_end = c.config.sim.duration;
      const std::vector<AddressEvent> expected = pull(calendar, t_end, 256, 1);
      ASSERT_GT(expected.size(), 1500u);
      // Windows cut at each ask, and run on past it (kept for the next asks).
      for (const bool ahead : {false, true}) {
        for (const std::size_t most : {1, 7, 256}) {
          FiringSchedule again(c.config.pixel, c.config.sim, photocurrents, map, tile);
          again.run_windows_ahead(ahead);
          expect_same(pull(again, t_end, most, most), expected);
        }
      }
    }
  }
}

TEST(FiringSchedule, TilesTakenInTurnOnOneThreadKeepTheirOwnWindows) {
  // A window's buffers pass from tile to tile on a thread once taken; a tile with firings left
  // keeps its own. Three tiles asked for a few firings in turn give what each gives alone.
  const Case c = cases()[1];
  const Photocurrents photocurrents(c.scene, c.config.pixel);
  const AddressMap map(c.config.array);
  std::vector<std::unique_ptr<FiringSchedule>> alone, turns;
  std::vector<std::vector<AddressEvent>> expected, got(3);
  for (std::uint32_t tile = 0; tile < 3; ++tile) {
    FiringSchedule s(c.config.pixel, c.config.sim, photocurrents, map, tile);
    expected.push_back(pull(s, c.config.sim.duration, 256, 3));
    turns.push_back(std::make_unique<FiringSchedule>(c.config.pixel, c.config.sim, photocurrents, map, tile));
  }
  std::vector<AddressEvent> batch(5);
  for (bool any = true; any;) {
    any = false;
    for (std::size_t tile = 0; tile < 3; ++tile) {
      const std::size_t n = turns[tile]->fill(batch.data(), 5, c.config.sim.duration);
      got[tile].insert(got[tile].end(), batch.begin(), batch.begin() + static_cast<std::ptrdiff_t>(n));
      any |= n > 0;
    }
  }
  for (std::size_t tile = 0; tile < 3; ++tile) expect_same(got[tile], expected[tile]);
}

// Windows are taken where they cost less: a moving scene in which a single pixel of the tile
// changes a thousand times a second stays on the calendar (each window would visit every pixel for
// about two wake-ups), one in which half of them change takes windows, as does one whose pixels
// fire several times a frame; a still scene with shot noise takes them unless a swing holds fewer
// than ten electrons.
TEST(FiringSchedule, WindowsWhereTheyCostLessThanTheCalendar) {
  SensorConfig c = exact_sensor(16, 16, 16);
  const AddressMap map(c.array);
  const auto windowed = [&](const std::function<double(int, int)>& second, double period) {
    const Photocurrents moving(
        make_scene({make_image(16, 16, [](int, int) { return 0.5; }), make_image(16, 16, second)}, period, true),
        c.pixel);
    return FiringSchedule(c.pixel, c.sim, moving, map, 0).windowed();
  };
  const auto half = [](int x, int) { return x < 8 ? 1.0 : 0.5; };
  const auto one = [](int x, int y) { return x == 3 && y == 5 ? 1.0 : 0.5; };
  // exact_sensor: 100 fC at up to 1 pA, so 5 to 10 firings a second.
  EXPECT_TRUE(windowed(half, 1.0));
  EXPECT_TRUE(windowed(half, 1e-3));
  EXPECT_FALSE(windowed(one, 1e-3));
  EXPECT_TRUE(windowed(one, 1.0));
  c.pixel.shot_noise = true;
  const Photocurrents still(make_scene({make_image(16, 16, [](int, int) { return 0.5; })}), c.pixel);
  EXPECT_TRUE(FiringSchedule(c.pixel, c.sim, still, map, 0).windowed());
  // Nine electrons a swing: counts spread by a third, past what a window makes room for.
  c.pixel.c_int = 9 * 1.602176634e-19 / c.pixel.dv_int;
  EXPECT_FALSE(FiringSchedule(c.pixel, c.sim, still, map, 0).windowed());
  c.pixel.c_int = 11 * 1.602176634e-19 / c.pixel.dv_int;
  EXPECT_TRUE(FiringSchedule(c.pixel, c.sim, still, map, 0).windowed());
}

}  // namespace
}  // namespace aesim
