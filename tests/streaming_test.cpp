// Records streamed, not hoarded: the merge across tiles is exact whatever the windows and threads,
// the writers stream the same bytes as formatting each event on its own, errors in a writer end
// the run, latency statistics stay exact (or bounded) in bounded memory, and the tiles' worker
// threads share out every tile and start clear of their creator's CPU.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <tuple>
#include <random>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <pthread.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "aesim/event_files/events_csv.hpp"
#include "aesim/array/address_map.hpp"
#include "aesim/events/event_merger.hpp"
#include "aesim/events/event_stream.hpp"
#include "aesim/events/latency_recorder.hpp"
#include "aesim/events/timestamps.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "aesim/threads/thread_placement.hpp"
#include "aesim/threads/worker_pool.hpp"

namespace aesim {
namespace {

// 80x80 pixels in 32x32 tiles (partial tiles at the edges), a disc crossing a grey background in
// three frames, pure ALOHA without contention detection (ghosts), random phases and mismatch.
SensorConfig busy_sensor() {
  SensorConfig c = testing::exact_sensor(80, 80, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.contention_detect = false;
  c.bus.t_event = 2e-6;
  c.pixel.i_max = 20e-12;
  c.pixel.mismatch = 0.03;
  c.pixel.initial = InitialState::Random;
  c.sim.duration = 0.15;
  c.sim.seed = 5;
  return c;
}

Scene disc_scene() {
  std::vector<Image> frames;
  for (int f = 0; f < 3; ++f) {
    frames.push_back(testing::make_image(80, 80, [f](int x, int y) {
      const double dx = x - (20 + 20 * f), dy = y - 40;
      return dx * dx + dy * dy < 15 * 15 ? 1.0 : 0.2;
    }));
  }
  return testing::make_scene(std::move(frames), 0.13);
}

SimulationResult run_with(const SensorConfig& c, const Photocurrents& p, int threads, double window_events) {
  SensorConfig copy = c;
  copy.sim.threads = threads;
  SimulationRequest request = testing::with_truth();
  request.window_events = window_events;
  return simulate(copy.resolved(), p, request);
}

bool same(const AddressEvent& a, const AddressEvent& b) {
  return a.t == b.t && a.x == b.x && a.y == b.y && a.tile == b.tile && a.bus_address == b.bus_address &&
         a.flags == b.flags;
}

TEST(Streaming, WindowsAndThreadsDoNotChangeTheRecords) {
  const SensorConfig c = busy_sensor();
  const Photocurrents p(disc_scene(), c.pixel);
  // One window: the whole run merged at once, as a run that held every event would.
  const SimulationResult whole = run_with(c, p, 1, 1e15);
  const auto& events = whole.log.events();
  const auto& truth = whole.log.truth();
  ASSERT_GT(events.size(), 40000u);
  ASSERT_GT(whole.log.totals().ghost, 10u);
  EXPECT_EQ(events.size(), whole.log.totals().delivered);
  EXPECT_EQ(truth.size(), whole.log.totals().fired);
  auto key = [](const AddressEvent& e) { return std::make_tuple(e.t, e.tile, e.bus_address); };
  for (std::size_t i = 1; i < events.size(); ++i) ASSERT_LT(key(events[i - 1]), key(events[i])) << i;
  for (std::size_t i = 1; i < truth.size(); ++i) ASSERT_LT(key(truth[i - 1].firing), key(truth[i].firing)) << i;

  // Windows of two firings a pixel and more let the tiles' windows of firings run on past them.
  for (const auto& [threads, window] :
       std::vector<std::pair<int, double>>{{1, 40}, {2, 300}, {3, 5000}, {1, 13000}, {2, 20000}}) {
    SCOPED_TRACE(fmt::format("{} threads, windows of {} events", threads, window));
    const SimulationResult streamed = run_with(c, p, threads, window);
    ASSERT_EQ(streamed.log.events().size(), events.size());
    for (std::size_t i = 0; i < events.size(); ++i) ASSERT_TRUE(same(streamed.log.events()[i], events[i])) << i;
    ASSERT_EQ(streamed.log.truth().size(), truth.size());
    for (std::size_t i = 0; i < truth.size(); ++i) {
      ASSERT_TRUE(same(streamed.log.truth()[i].firing, truth[i].firing)) << i;
      ASSERT_EQ(streamed.log.truth()[i].fate, truth[i].fate) << i;
    }
  }
}

// The 1 bits the buses carried (the power model's bus energy) are summed per pixel after the run:
// they must equal the sum over every fired event's address, ghosts (which no pixel fired) aside.
TEST(Streaming, AddressOnesAreThoseOfEveryFiredEvent) {
  const SensorConfig c = busy_sensor();
  const Photocurrents p(disc_scene(), c.pixel);
  const SimulationResult r = run_with(c, p, 2, 1000);
  std::uint64_t expected = 0;
  for (const TruthRecord& t : r.log.truth()) expected += static_cast<std::uint64_t>(__builtin_popcount(t.firing.bus_address));
  ASSERT_GT(r.log.totals().ghost, 10u);
  ASSERT_GT(expected, 100000u);
  EXPECT_EQ(r.log.address_ones(), expected);
  // A log that counts no pixels sums them per event.
  EventLog bare(1, false);
  AddressEvent e;
  e.bus_address = 0x2F5;
  bare.fired(e);
  bare.fired_all(&e, 1);
  EXPECT_EQ(bare.address_ones(), 14u);
}

// A ghost is the OR of the colliding addresses: with tiles whose sides are not powers of two it
// may name a column past its tile or a row past the array's bottom, and a receiver under test may
// put out any address. Such an output is counted in its tile's counters but at no pixel (it was
// once counted past the end of the per-pixel counters, which corrupted the truth records).
TEST(Streaming, AnOutputNamingNoPixelOfItsTileIsCountedAtNoPixel) {
  ArrayParams array;
  array.rows = 79;
  array.cols = 130;
  array.tile_rows = 27;
  array.tile_cols = 37;
  const AddressMap map(array);
  ASSERT_EQ(map.tiles(), 12);
  EventLog log(map.tiles(), false);
  log.count_pixels(map, 1.0);
  AddressEvent ghost;
  ghost.tile = 11;                       // the bottom-right tile: x from 111, y from 54
  ghost.bus_address = (31u << 6) | 63u;  // local (63, 31): past the array on both sides
  const PixelAddress at = map.locate(ghost.tile, ghost.bus_address);
  ghost.x = at.x;
  ghost.y = at.y;
  ghost.flags = kGhostEvent;
  log.output(ghost);
  ghost.tile = 0;                        // local (63, 31) in a full tile: x past its 37 columns,
  const PixelAddress in_next = map.locate(ghost.tile, ghost.bus_address);  // in tile 1's
  ghost.x = in_next.x;
  ghost.y = in_next.y;
  ASSERT_LT(ghost.x, 130u);
  log.output(ghost);
  AddressEvent real = map.event_at({120, 70});
  real.flags = kGhostEvent;              // a ghost that happens to name a real pixel
  log.output(real);
  log.finish();
  EXPECT_EQ(log.totals().delivered, 3u);
  EXPECT_EQ(log.totals().ghost, 3u);
  const std::vector<std::uint32_t> per_pixel = log.output_per_pixel();
  EXPECT_EQ(std::accumulate(per_pixel.begin(), per_pixel.end(), 0u), 1u);
  EXPECT_EQ(per_pixel[70 * 130 + 120], 1u);
}

// End to end on such an array, with undetected collisions on two threads: every delivered row of
// the truth is an output event of the same pixel, and the truth is the one process per pixel
// baseline's.
TEST(Streaming, GhostsPastTheEdgeLeaveTheTruthIntact) {
  SensorConfig c = testing::exact_sensor(79, 130, 27);
  c.array.tile_cols = 37;
  c.bus.access = BusAccess::Aloha;
  c.bus.contention_detect = false;
  c.bus.t_event = 2e-6;
  c.pixel.i_max = 26e-12;
  c.pixel.mismatch = 0.1;
  c.pixel.t_reset = 1e-3;
  c.sim.duration = 0.3;
  c.sim.threads = 2;
  const Photocurrents p(testing::make_scene({testing::make_image(130, 79, [](int x, int y) {
                          return (x / 9 + y / 7) % 3 == 0 ? 1.0 : 0.3;
                        })}),
                        c.pixel);
  const SimulationResult event = simulate(c.resolved(), p, testing::with_truth());
  ASSERT_GT(event.log.totals().ghost, 100u);
  std::multiset<std::tuple<double, std::uint32_t, std::uint32_t>> outputs;
  for (const AddressEvent& e : event.log.events()) {
    if (!(e.flags & kGhostEvent)) outputs.insert({e.t, e.x, e.y});
  }
  std::size_t delivered = 0;
  for (const TruthRecord& r : event.log.truth()) {
    if (r.fate != Fate::Delivered) continue;
    ++delivered;
    ASSERT_EQ(outputs.count({r.t_deliver, r.firing.x, r.firing.y}), 1u) << r.firing.x << "," << r.firing.y;
  }
  EXPECT_EQ(delivered, outputs.size());
  SensorConfig baseline = c;
  baseline.sim.fidelity = Fidelity::PixelProcesses;
  const SimulationResult processes = simulate(baseline.resolved(), p, testing::with_truth());
  ASSERT_EQ(processes.log.truth().size(), event.log.truth().size());
  for (std::size_t i = 0; i < event.log.truth().size(); ++i) {
    ASSERT_TRUE(same(processes.log.truth()[i].firing, event.log.truth()[i].firing)) << i;
  }
}

// A record of `tile` at time t, from a random pixel of its 32x32 tile.
AddressEvent record_at(double t, std::uint32_t tile, std::mt19937_64& rng) {
  AddressEvent e;
  e.t = t;
  e.tile = tile;
  e.bus_address = static_cast<std::uint32_t>(rng() % 1024);
  e.x = e.bus_address % 32;
  e.y = e.bus_address / 32;
  return e;
}

// A tile's records into a merge's batch, in the (time, address) order a tile produces them.
void add_in_tile_order(TileRecords& batch, std::uint32_t tile, std::vector<AddressEvent>& mine) {
  std::sort(mine.begin(), mine.end(), [](const AddressEvent& a, const AddressEvent& b) {
    return std::make_pair(a.t, a.bus_address) < std::make_pair(b.t, b.bus_address);
  });
  for (const AddressEvent& e : mine) batch.events[tile].push_back(TileEvent::of(e));
}

// The merge orders by (time, tile, bus address) whatever the windows: many records share a time
// (a coarse grid of times, zero among them, written both as +0.0 and -0.0, which are the same
// time), across tiles and within one. Expected: the whole set sorted by the triple.
// Against a stable sort of every record on (time, tile, address): few instants (every bucket of the
// merge's counting sort crowded, one slice), and many records over many instants (several slices,
// a bucket now and then holding two or more tiles' records, some instants shared by many).
TEST(Streaming, TheMergeOrdersTiesByTileThenAddress) {
  constexpr std::uint32_t kTiles = 5;
  for (const auto& [per_tile, instants] : {std::pair<int, int>{400, 50}, {8000, 20000}}) {
    std::mt19937_64 rng(11);
    std::vector<AddressEvent> all;
    TileRecords batch(kTiles);
    for (std::uint32_t tile = 0; tile < kTiles; ++tile) {
      std::vector<AddressEvent> mine;
      for (int i = 0; i < per_tile; ++i) {
        // One record in eight at one of a few instants every tile shares; with many instants, the
        // others anywhere between them.
        const bool shared = rng() % 8 == 0;
        const auto instant = shared ? rng() % 8 * (instants / 8) : rng() % instants;
        const double within = shared || instants < 1000 ? 0.0 : static_cast<double>(rng() % 1000) / 1000;
        double t = 1e-6 * (static_cast<double>(instant) + within);
        if (t == 0 && rng() % 2) t = -0.0;
        mine.push_back(record_at(t, tile, rng));
      }
      add_in_tile_order(batch, tile, mine);
      all.insert(all.end(), mine.begin(), mine.end());
    }
    std::stable_sort(all.begin(), all.end(), [](const AddressEvent& a, const AddressEvent& b) {
      return std::make_tuple(a.t, a.tile, a.bus_address) < std::make_tuple(b.t, b.tile, b.bus_address);
    });
    EventCollector out;
    EventMerger merger(kTiles, out);
    TileRecords empty(kTiles);
    // A cut between two times: part now, the rest next.
    merger.merge(batch, 1e-6 * (static_cast<double>(instants) * 0.4 + 0.5));
    merger.merge(empty, std::numeric_limits<double>::infinity());
    ASSERT_EQ(out.events().size(), all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      const AddressEvent& got = out.events()[i];
      ASSERT_EQ(got.t, all[i].t) << i;  // -0.0 == +0.0
      ASSERT_EQ(got.tile, all[i].tile) << i;
      ASSERT_EQ(got.bus_address, all[i].bus_address) << i;
      ASSERT_EQ(got.x, all[i].x) << i;
    }
  }
}

// The merge cuts a window's span of time into slices of equal length and sizes each slice's
// buckets for its share of the records: a burst (nine records in ten within a hundredth of the span,
// at distinct times) puts many times that share in one slice, and many records in each of its
// buckets. Expected: the whole set sorted by (time, tile, address), as without the burst.
TEST(Streaming, TheMergeOrdersABurstThatCrowdsOneSlice) {
  constexpr std::uint32_t kTiles = 3;
  constexpr int kPerTile = 30000;
  std::mt19937_64 rng(5);
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> expected;
  TileRecords batch(kTiles);
  for (std::uint32_t tile = 0; tile < kTiles; ++tile) {
    std::vector<AddressEvent> mine;
    for (int i = 0; i < kPerTile; ++i) {
      const double u = static_cast<double>(rng() % 1000000) / 1000000;
      mine.push_back(record_at(rng() % 10 == 0 ? u : 0.5 + 0.01 * u, tile, rng));
    }
    add_in_tile_order(batch, tile, mine);
    for (const AddressEvent& e : mine) expected.emplace_back(e.t, e.tile, e.bus_address);
  }
  std::sort(expected.begin(), expected.end());
  EventCollector out;
  EventMerger merger(kTiles, out);
  merger.merge(batch, std::numeric_limits<double>::infinity());
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> got;
  for (const AddressEvent& e : out.events()) got.emplace_back(e.t, e.tile, e.bus_address);
  EXPECT_EQ(got, expected);
}

// A tile's events may reach the log out of order (simultaneous SystemC processes run in any order):
// the merge sorts them whatever way they came, one by one or a batch at a time; in order, the log's
// own check as they come spares the merge its pass over them. Enough records for the merge to cut
// its window into slices, so that a run taken as sorted when it is not would come out of order.
TEST(Streaming, TheLogsEventsComeOutInOrderWhateverOrderTheyCameIn) {
  constexpr int kPerTile = 20000;
  std::vector<std::vector<AddressEvent>> tiles(2);
  for (std::uint32_t tile = 0; tile < 2; ++tile) {
    for (int k = 0; k < kPerTile; ++k) {
      AddressEvent e;
      e.t = 1e-7 * k + 5e-8 * tile;
      e.tile = tile;
      e.bus_address = static_cast<std::uint32_t>(k % 1000);
      e.x = e.bus_address;
      tiles[tile].push_back(e);
    }
  }
  // Out of order within a window (never before the time the last hand-over named): tile 0 in its
  // first, tile 1 in its second; an early record comes near the window's end, a late one early.
  std::swap(tiles[0][100], tiles[0][kPerTile / 2 - 1000]);
  std::swap(tiles[1][kPerTile / 2 + 100], tiles[1][kPerTile - 1000]);
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> expected;
  for (const auto& mine : tiles) {
    for (const AddressEvent& e : mine) expected.emplace_back(e.t, e.tile, e.bus_address);
  }
  std::sort(expected.begin(), expected.end());
  for (const bool batch : {false, true}) {
    SCOPED_TRACE(batch ? "a batch at a time" : "one at a time");
    EventLog log(2, false);
    // Two windows a tile, the second from the middle on.
    for (const int half : {0, 1}) {
      for (const auto& mine : tiles) {
        const AddressEvent* first = mine.data() + half * kPerTile / 2;
        if (batch) {
          log.fired_and_delivered(first, kPerTile / 2);
        } else {
          for (int k = 0; k < kPerTile / 2; ++k) log.output(first[k]);
        }
      }
      log.hand_over(1e-7 * kPerTile / 4);
    }
    log.finish();
    std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> got;
    for (const AddressEvent& e : log.events()) got.emplace_back(e.t, e.tile, e.bus_address);
    EXPECT_EQ(got, expected);
  }
}

// A stream that fails part-way, as a full disk would.
class FailingStream : public EventStream {
 public:
  void events(const AddressEvent*, std::size_t count) override {
    seen_ += count;
    if (seen_ > 1000) throw std::runtime_error("disk full");
  }

 private:
  std::size_t seen_ = 0;
};

TEST(Streaming, BufferedEventsKeepEveryFieldAtTheLimitsOfTheArray) {
  // The widest bus address a valid array can give: 65535 columns need 16 bits, 256 rows 8, and
  // 65535 x 256 is within the 2^24 pixels an array may have.
  ArrayParams array;
  array.cols = 65535;
  array.rows = 256;
  array.tile_cols = 65535;
  array.tile_rows = 256;
  const AddressMap map(array);
  ASSERT_LE(map.bus_bits(), 25);
  const std::uint32_t widest = map.bus_address({65534, 255});
  for (const std::uint8_t flags : {std::uint8_t(kNormalEvent), std::uint8_t(kGhostEvent)}) {
    AddressEvent e;
    e.t = 1234.5678901234567;
    e.x = 65534;
    e.y = 255;
    e.tile = 7;
    e.bus_address = widest;
    e.flags = flags;
    const AddressEvent back = TileEvent::of(e).in_tile(7);
    EXPECT_EQ(back.t, e.t);
    EXPECT_EQ(back.x, e.x);
    EXPECT_EQ(back.y, e.y);
    EXPECT_EQ(back.tile, e.tile);
    EXPECT_EQ(back.bus_address, e.bus_address);
    EXPECT_EQ(back.flags, e.flags);
  }
}

// On one thread the merge (and so the writer) runs on a thread of its own; on more, among the
// tiles' threads: either way its error ends the run.
TEST(Streaming, AWriterErrorEndsTheRun) {
  for (const int threads : {1, 2}) {
    SCOPED_TRACE(fmt::format("{} threads", threads));
    SensorConfig c = busy_sensor();
    c.sim.threads = threads;
    const Photocurrents p(disc_scene(), c.pixel);
    FailingStream failing;
    SimulationRequest request;
    request.stream = &failing;
    request.window_events = 500;
    EXPECT_THROW(simulate(c.resolved(), p, request), std::runtime_error);
  }
}

TEST(Streaming, ARunWithoutRecordsCountsTheSame) {
  const SensorConfig c = busy_sensor();
  const Photocurrents p(disc_scene(), c.pixel);
  SimulationRequest counters_only;
  counters_only.keep_events = false;
  const SimulationResult counted = simulate(c.resolved(), p, counters_only);
  const SimulationResult kept = run_with(c, p, 2, 1000);
  EXPECT_TRUE(counted.log.events().empty());
  EXPECT_EQ(counted.log.totals().fired, kept.log.totals().fired);
  EXPECT_EQ(counted.log.totals().delivered, kept.log.totals().delivered);
  EXPECT_EQ(counted.log.totals().ghost, kept.log.totals().ghost);
  EXPECT_EQ(counted.log.output_per_pixel(), kept.log.output_per_pixel());
}

// The log's per-pixel counters (firings and outputs, in all and within the counting window: the
// histogram image and the sizing metrics) are those of the run's records, counted pixel by pixel
// from the truth and the output events: whether the log counts each firing as it comes or takes a
// tile's firings from its schedule after the run (on a bus that delivers or loses each firing as
// it fires: windows count them as they make them or, still and without shot noise, work them out
// from the pixels' periods), on one thread or two, with records or counters only.
TEST(Streaming, PerPixelCountsAreThoseOfTheRecords) {
  struct Case {
    const char* name;
    BusAccess access;
    bool detect;
    bool moving;
    bool shot_noise = false;
  };
  const Scene still = testing::make_scene({disc_scene().frames[1]});
  for (const Case& k : {Case{"ALOHA, ghosts", BusAccess::Aloha, false, false},
                        Case{"ALOHA, detected", BusAccess::Aloha, true, false},
                        Case{"ideal", BusAccess::Ideal, true, false},
                        Case{"arbitrated", BusAccess::Arbitrated, true, false},
                        Case{"ALOHA, moving", BusAccess::Aloha, false, true},
                        Case{"ALOHA, shot noise", BusAccess::Aloha, false, false, true},
                        Case{"ALOHA, moving, shot noise", BusAccess::Aloha, true, true, true}}) {
    SensorConfig c = busy_sensor();
    c.pixel.shot_noise = k.shot_noise;
    c.bus.access = k.access;
    c.bus.contention_detect = k.detect;
    c.analysis.window = 0.6 * c.sim.duration;
    const Photocurrents p(k.moving ? disc_scene() : still, c.pixel);
    const AddressMap map(c.resolved().array);
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(fmt::format("{}, {} threads", k.name, threads));
      const SimulationResult r = run_with(c, p, threads, 700);
      const std::size_t pixels = static_cast<std::size_t>(map.rows()) * static_cast<std::size_t>(map.cols());
      std::vector<std::uint32_t> fired(pixels), fired_within(pixels), output(pixels), output_within(pixels);
      const auto at = [&map](const AddressEvent& e) { return std::size_t(e.y) * std::size_t(map.cols()) + e.x; };
      for (const TruthRecord& t : r.log.truth()) {
        ++fired[at(t.firing)];
        fired_within[at(t.firing)] += t.firing.t <= c.analysis.window;
      }
      std::uint64_t ghosts = 0;
      for (const AddressEvent& e : r.log.events()) {
        const bool ghost = (e.flags & kGhostEvent) != 0;
        ghosts += ghost;
        if (!map.names_pixel(e)) continue;
        ++output[at(e)];
        output_within[at(e)] += !ghost && e.t <= c.analysis.window;
      }
      ASSERT_GT(r.log.truth().size(), 20000u);
      if (k.access == BusAccess::Aloha) {
        ASSERT_GT(r.log.totals().collided, 100u);
      }
      if (k.access == BusAccess::Aloha && !k.detect) {
        ASSERT_GT(ghosts, 10u);
      }
      ASSERT_LT(std::count(fired_within.begin(), fired_within.end(), 0u), std::ptrdiff_t(pixels / 10));
      EXPECT_EQ(r.log.fired_per_pixel(), fired);
      EXPECT_EQ(r.log.window_per_pixel(), fired_within);
      EXPECT_EQ(r.log.output_per_pixel(), output);
      EXPECT_EQ(r.log.window_output_per_pixel(), output_within);
      SensorConfig copy = c;
      copy.sim.threads = threads;
      SimulationRequest counters_only;
      counters_only.keep_events = false;
      const SimulationResult counted = simulate(copy.resolved(), p, counters_only);
      EXPECT_EQ(counted.log.fired_per_pixel(), fired);
      EXPECT_EQ(counted.log.window_per_pixel(), fired_within);
      EXPECT_EQ(counted.log.output_per_pixel(), output);
      EXPECT_EQ(counted.log.window_output_per_pixel(), output_within);
    }
  }
}

// The CSV writer's integer path against formatting each timestamp as a double (the reference's
// definition: t_us with as many decimals as the tick resolves), over ticks that are and are not
// whole decimal units.
TEST(Streaming, CsvIntegerTimestampsMatchTheDecimalDefinition) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> when(0, 2000);
  for (double tick : {1e-6, 1e-7, 1e-8, 1e-9, 1e-12, 2e-6, 17.36111e-9, 0.5e-6}) {
    std::vector<AddressEvent> events;
    for (int i = 0; i < 2000; ++i) {
      AddressEvent e;
      e.t = when(rng);
      e.x = static_cast<std::uint32_t>(i % 64);
      e.y = static_cast<std::uint32_t>(i % 61);
      e.tile = static_cast<std::uint32_t>(i % 4);
      e.flags = static_cast<std::uint8_t>(i % 2);
      events.push_back(e);
    }
    std::ostringstream written;
    write_events_csv(written, events, tick);
    const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(tick / 1e-6) - 1e-9)));
    std::string expected = "t_us,x,y,tile,flags\n";
    for (const AddressEvent& e : events) {
      const double t_us = static_cast<double>(timestamp_ticks(e.t, tick)) * (tick / 1e-6);
      expected += fmt::format("{:.{}f},{},{},{},{}\n", t_us, decimals, e.x, e.y, e.tile, e.flags);
    }
    EXPECT_EQ(written.str(), expected) << "tick " << tick;
  }
}

TEST(LatencyRecorder, NearestRankOverZerosAndWaits) {
  LatencyRecorder r;
  for (int i = 0; i < 98; ++i) r.add(0);
  r.add(2e-6);
  r.add(1e-6);
  const LatencyStats s = r.stats();
  EXPECT_DOUBLE_EQ(s.p99, 1e-6);  // rank ceil(0.99 * 100) = 99: the first nonzero wait
  EXPECT_DOUBLE_EQ(s.max, 2e-6);
  EXPECT_DOUBLE_EQ(s.mean, 3e-8);
}

TEST(LatencyRecorder, BinnedPastTheLimitStaysWithinABin) {
  std::mt19937_64 rng(9);
  std::lognormal_distribution<double> wait(-12, 2);
  LatencyRecorder exact(1u << 20), tile_a(50), tile_b(50), binned(100);
  for (int i = 0; i < 20000; ++i) {
    const double w = i % 7 == 0 ? 0.0 : wait(rng);
    exact.add(w);
    (i % 2 ? tile_a : tile_b).add(w);
  }
  binned.absorb(tile_a);
  binned.absorb(tile_b);
  const LatencyStats e = exact.stats(), b = binned.stats();
  EXPECT_EQ(b.max, e.max);
  EXPECT_NEAR(b.mean, e.mean, 1e-12 * e.mean);
  EXPECT_GE(b.p99, e.p99);
  EXPECT_LE(b.p99, e.p99 * (1 + std::ldexp(1.0, -12)));
}

TEST(WorkerPool, EveryIndexRunsOnceAndTheFirstErrorComesBack) {
  WorkerPool pool(3);
  for (int round = 0; round < 50; ++round) {
    std::vector<std::atomic<int>> runs(97);
    pool.for_each(runs.size(), [&](std::size_t i) { ++runs[i]; });
    for (const auto& r : runs) ASSERT_EQ(r.load(), 1);
  }
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.for_each(40,
                             [&](std::size_t i) {
                               ++ran;
                               if (i % 10 == 3) throw std::runtime_error("tile failed");
                             }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 40);  // the other indices still ran
  std::atomic<int> after{0};
  pool.for_each(5, [&](std::size_t) { ++after; });  // the error was handed back, not kept
  EXPECT_EQ(after.load(), 5);
}

// A thread kept off its creator's CPU may run on every CPU the process may use but that one; a
// creator with a single CPU leaves it alone. The creator is pinned for the first check and given
// back its CPUs after.
TEST(ThreadPlacement, ANewThreadMayRunAnywhereButItsCreatorsCpu) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  const int cpu = sched_getcpu();
  ASSERT_GE(cpu, 0);
  cpu_set_t here;
  CPU_ZERO(&here);
  CPU_SET(cpu, &here);
  ASSERT_EQ(sched_setaffinity(0, sizeof here, &here), 0);
  std::mutex m;
  std::condition_variable cv;
  bool go = false;
  std::thread t([&] {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return go; });
  });
  // Pinned, the creator's own mask is now one CPU: the thread inherited it, and it is left alone.
  keep_off_callers_cpu(t);
  cpu_set_t mask;
  CPU_ZERO(&mask);
  ASSERT_EQ(pthread_getaffinity_np(t.native_handle(), sizeof mask, &mask), 0);
  EXPECT_TRUE(CPU_EQUAL(&mask, &here));
  {
    std::lock_guard<std::mutex> lock(m);
    go = true;
  }
  cv.notify_all();
  t.join();
  ASSERT_EQ(sched_setaffinity(0, sizeof allowed, &allowed), 0);
  if (CPU_COUNT(&allowed) < 2) GTEST_SKIP() << "one CPU allowed: nowhere else to put a thread";

  // With every CPU allowed again: only the creator's CPU is left out, read just before and just
  // after the call (the creator could move between, not twice within so short a span).
  std::thread u([&] {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return !go; });
  });
  const int before = sched_getcpu();
  keep_off_callers_cpu(u);
  const int after = sched_getcpu();
  CPU_ZERO(&mask);
  ASSERT_EQ(pthread_getaffinity_np(u.native_handle(), sizeof mask, &mask), 0);
  {
    std::lock_guard<std::mutex> lock(m);
    go = false;
  }
  cv.notify_all();
  u.join();
  EXPECT_EQ(CPU_COUNT(&mask), CPU_COUNT(&allowed) - 1);
  cpu_set_t left_out;
  CPU_XOR(&left_out, &mask, &allowed);
  ASSERT_EQ(CPU_COUNT(&left_out), 1);
  EXPECT_TRUE(CPU_ISSET(before, &left_out) || CPU_ISSET(after, &left_out));
}

// Kept off its creator's CPU only for its start: by the time its body runs, the thread may run on
// every CPU its creator may (more threads than CPUs still balance), and a creator with a single
// CPU shares it.
TEST(ThreadPlacement, AStartedThreadMayRunOnEveryCpuOnceItRuns) {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  cpu_set_t seen;
  auto body = [&seen] {
    CPU_ZERO(&seen);
    sched_getaffinity(0, sizeof seen, &seen);
  };
  for (int i = 0; i < 20; ++i) {
    std::thread t = start_off_callers_cpu(body);
    t.join();
    ASSERT_TRUE(CPU_EQUAL(&seen, &allowed)) << "start " << i;
  }
  const int cpu = sched_getcpu();
  cpu_set_t here;
  CPU_ZERO(&here);
  CPU_SET(cpu, &here);
  ASSERT_EQ(sched_setaffinity(0, sizeof here, &here), 0);
  int ran_on = -1;
  std::thread t = start_off_callers_cpu([&ran_on] { ran_on = sched_getcpu(); });
  t.join();
  ASSERT_EQ(sched_setaffinity(0, sizeof allowed, &allowed), 0);
  EXPECT_EQ(ran_on, cpu);
}

// A collector keeps every record in order whatever the chunks' sizes, across its growth (to blocks
// of 8 MiB and more), the same as one insert of them all.
TEST(EventCollectorTest, KeepsEveryRecordInOrderAcrossItsGrowth) {
  std::vector<AddressEvent> all(600000);
  for (std::size_t i = 0; i < all.size(); ++i) {
    all[i].t = 1e-6 * static_cast<double>(i);
    all[i].x = static_cast<std::uint16_t>(i % 1024);
    all[i].y = static_cast<std::uint16_t>(i / 1024 % 1024);
    all[i].tile = static_cast<std::uint32_t>(i % 7);
  }
  EventCollector collector;
  std::mt19937 draws(5);
  for (std::size_t at = 0; at < all.size();) {
    const std::size_t n = std::min<std::size_t>(all.size() - at, std::uniform_int_distribution<std::size_t>(0, 20000)(draws));
    collector.events(all.data() + at, n);
    at += n;
  }
  ASSERT_GE(collector.events().capacity() * sizeof(AddressEvent), std::size_t(8) << 20);
  ASSERT_EQ(collector.events().size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    ASSERT_EQ(collector.events()[i].t, all[i].t) << i;
    ASSERT_EQ(collector.events()[i].x, all[i].x) << i;
    ASSERT_EQ(collector.events()[i].tile, all[i].tile) << i;
  }
}

}  // namespace
}  // namespace aesim
