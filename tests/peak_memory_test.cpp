// Memory does not grow with the run's length: the allocator's peak over a run 100x longer is the
// same, within the slack of buffer growth, whether the run streams its events or counts them.
#include <gtest/gtest.h>

#include <limits>

#include "aesim/events/event_merger.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/counting_allocator.hpp"
#include "support/scenes.hpp"

namespace aesim {
namespace {

// Checks order and counts what it is given, keeping nothing: a writer with no file.
class CheckingStream : public EventStream {
 public:
  void events(const AddressEvent* first, std::size_t count) override {
    for (std::size_t i = 0; i < count; ++i) {
      if (first[i].t < last_) ++out_of_order_;
      last_ = first[i].t;
    }
    seen_ += count;
  }
  std::size_t seen_ = 0, out_of_order_ = 0;
  double last_ = 0;
};

// 64x64 uniform full light on the aloha constants: 4096 pixels at 10 Hz, ~41,000 events/s.
SensorConfig bright_sensor(double duration) {
  SensorConfig c = testing::exact_sensor(64, 64, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.t_event = 100e-9;
  c.pixel.initial = InitialState::Random;
  c.sim.duration = duration;
  return c;
}

struct Peak {
  std::size_t bytes;
  std::uint64_t events;
};

Scene full_light() { return testing::make_scene({testing::make_image(64, 64, [](int, int) { return 1.0; })}); }

// A counting run keeps one tile's schedule per thread while it runs: on one thread, so which
// tiles overlap in time does not change the peak.
Peak peak_of(double duration, bool keep_events, const Scene& scene = full_light()) {
  SensorConfig c = bright_sensor(duration);
  c.sim.threads = keep_events ? 2 : 1;
  const Photocurrents p(scene, c.pixel);
  CheckingStream stream;
  SimulationRequest request;
  request.keep_events = keep_events;
  request.stream = &stream;
  request.window_events = 4096;
  const std::size_t before = testing::allocated_bytes();
  testing::reset_peak();
  std::uint64_t delivered = 0;
  {
    const SimulationResult r = simulate(c.resolved(), p, request);
    delivered = r.log.totals().delivered;
  }
  EXPECT_EQ(stream.out_of_order_, 0u);
  if (keep_events) {
    EXPECT_EQ(stream.seen_, delivered);
  }
  return {testing::peak_allocated_bytes() - before, delivered};
}

TEST(PeakMemory, AStreamingRunDoesNotGrowWithItsLength) {
  const Peak short_run = peak_of(0.5, true), long_run = peak_of(50.0, true);
  ASSERT_GT(long_run.events, 90 * short_run.events);
  // Held as records, the long run's events alone would take 32 bytes each (65 MB).
  EXPECT_LT(long_run.bytes, short_run.bytes + (256u << 10))
      << short_run.bytes << " bytes for " << short_run.events << " events, " << long_run.bytes << " for "
      << long_run.events;
}

// The first window is sized on the light the pixels start in, up to its first change: a thousandth
// of full light for a quarter second, then full light held. Sized on the dim light alone, the first
// window would hold the whole run (about 100 s at its 41 events/s).
TEST(PeakMemory, AStreamingRunStartingDimDoesNotGrowWithItsLength) {
  const Scene dim_then_bright = testing::make_scene(
      {testing::make_image(64, 64, [](int, int) { return 1e-3; }), testing::make_image(64, 64, [](int, int) { return 1.0; })},
      0.25);
  const Peak short_run = peak_of(5.0, true, dim_then_bright), long_run = peak_of(50.0, true, dim_then_bright);
  ASSERT_GT(long_run.events, 9 * short_run.events);
  EXPECT_LT(long_run.bytes, short_run.bytes + (256u << 10))
      << short_run.bytes << " bytes for " << short_run.events << " events, " << long_run.bytes << " for "
      << long_run.events;
}

TEST(PeakMemory, ACountingRunDoesNotGrowWithItsLength) {
  // The short run spans more than one of a still tile's windows of firings (about four firings a
  // pixel, 0.4 s here), whose buffers are as large as they get by then.
  const Peak short_run = peak_of(0.5, false), long_run = peak_of(50.0, false);
  ASSERT_GT(long_run.events, 90 * short_run.events);
  EXPECT_LT(long_run.bytes, short_run.bytes + (64u << 10))
      << short_run.bytes << " bytes for " << short_run.events << " events, " << long_run.bytes << " for "
      << long_run.events;
  std::printf("peak %zu bytes for %llu events, %zu for %llu\n", short_run.bytes,
              static_cast<unsigned long long>(short_run.events), long_run.bytes,
              static_cast<unsigned long long>(long_run.events));
}

// A streaming run's record buffers are made the size of a window's records, not doubled past it:
// 256x256 pixels in 64 tiles, windows of 550 and then 1,100 records a tile (a little past 512
// and 1,024, where buffers grown by doubling would take 1,024 and 2,048 places). On two threads
// the tiles fill one set of buffers while the other is merged: the peak grows with the window by
// two sets' worth of records, 16 bytes each (by 1.69 times that, measured, with buffers grown by
// doubling).
TEST(PeakMemory, AStreamingRunsBuffersHoldItsWindowsRecords) {
  SensorConfig c = bright_sensor(1.0);
  c.array.rows = c.array.cols = 256;
  c.bus.access = BusAccess::Ideal;
  c.sim.threads = 2;
  const Photocurrents p(testing::make_scene({testing::make_image(256, 256, [](int, int) { return 1.0; })}), c.pixel);
  const auto peak_with = [&](double window_events) {
    CheckingStream stream;
    SimulationRequest request;
    request.keep_events = true;
    request.stream = &stream;
    request.window_events = window_events;
    const std::size_t before = testing::allocated_bytes();
    testing::reset_peak();
    { const SimulationResult r = simulate(c.resolved(), p, request); }
    EXPECT_EQ(stream.out_of_order_, 0u);
    EXPECT_GT(stream.seen_, 600000u);
    return testing::peak_allocated_bytes() - before;
  };
  constexpr double kSmall = 550.0 * 64, kLarge = 1100.0 * 64;
  const std::size_t small = peak_with(kSmall), large = peak_with(kLarge);
  const double records = 2 * (kLarge - kSmall) * sizeof(TileEvent);
  ASSERT_GT(large, small);
  EXPECT_LT(static_cast<double>(large - small), 1.35 * records)
      << small << " bytes with windows of " << kSmall << " records, " << large << " with " << kLarge;
}

// A rung that keeps its records until the end merges them all at once: the merge's own room is a
// slice's (about 4096 records, staged at 24 bytes and passed on at 32), not the run's. Two tiles
// of 500,000 records each, merged in one call: staging a whole tile's run would take 12 MB.
TEST(PeakMemory, TheMergeOfAWholeRunTakesTheRoomOfASlice) {
  constexpr std::size_t kPerTile = 500000;
  TileRecords batch(2);
  for (std::uint32_t tile = 0; tile < 2; ++tile) {
    for (std::size_t i = 0; i < kPerTile; ++i) {
      AddressEvent e;
      e.t = 1e-6 * static_cast<double>(2 * i + tile);
      e.tile = tile;
      e.bus_address = static_cast<std::uint32_t>(i % 1024);
      e.x = e.bus_address % 32;
      e.y = e.bus_address / 32;
      batch.events[tile].push_back(TileEvent::of(e));
    }
  }
  CheckingStream stream;
  EventMerger merger(2, stream);
  const std::size_t before = testing::allocated_bytes();
  testing::reset_peak();
  merger.merge(batch, std::numeric_limits<double>::infinity());
  const std::size_t peak = testing::peak_allocated_bytes() - before;
  EXPECT_EQ(stream.seen_, 2 * kPerTile);
  EXPECT_EQ(stream.out_of_order_, 0u);
  EXPECT_LT(peak, std::size_t(2) << 20) << peak << " bytes";
}

}  // namespace
}  // namespace aesim
