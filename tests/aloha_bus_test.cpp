// Event-fidelity buses on hand-made cases: pure ALOHA windows, chains, ghosts, arbitration.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "aesim/array/address_map.hpp"
#include "aesim/bus/aloha_bus.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

constexpr double kTau = 0.5;  // s: exactly representable, so "exactly tau apart" is exact

class EventBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    array_.rows = array_.cols = 32;
    array_.tile_rows = array_.tile_cols = 32;
  }
  AddressEvent firing(double t, std::uint32_t x, std::uint32_t y) const {
    const AddressMap map(array_);
    AddressEvent e;
    e.t = t;
    e.x = x;
    e.y = y;
    e.tile = map.tile_of({x, y});
    e.bus_address = map.bus_address({x, y});
    return e;
  }
  // Feeds the firings to a fresh ALOHA bus and returns the log.
  EventLog aloha(const std::vector<AddressEvent>& firings, bool detect) {
    EventLog log(1, true);
    const AddressMap map(array_);
    AlohaBus bus(log, map, kTau, detect);
    for (const AddressEvent& f : firings) bus.request(f);
    bus.finish();
    log.finish();
    return log;
  }
  std::vector<Fate> fates(const EventLog& log) {
    std::vector<Fate> v;
    for (const TruthRecord& r : log.truth()) v.push_back(r.fate);
    return v;
  }
  ArrayParams array_;
};

TEST_F(EventBusTest, CloserThanTauBothCollideFartherBothArrive) {
  EventLog close = aloha({firing(1.0, 1, 1), firing(1.0 + 0.4 * kTau, 2, 2)}, true);
  EXPECT_EQ(fates(close), (std::vector<Fate>{Fate::Collided, Fate::Collided}));
  EXPECT_EQ(close.totals().collided, 2u);
  EXPECT_TRUE(close.events().empty());

  EventLog far = aloha({firing(1.0, 1, 1), firing(1.0 + 1.5 * kTau, 2, 2)}, true);
  EXPECT_EQ(fates(far), (std::vector<Fate>{Fate::Delivered, Fate::Delivered}));
  ASSERT_EQ(far.events().size(), 2u);
  EXPECT_EQ(far.events()[1].t, 1.0 + 1.5 * kTau);
}

TEST_F(EventBusTest, ExactlyTauApartDoNotCollide) {
  // The window is open: (t - tau, t + tau).
  EventLog log = aloha({firing(1.0, 1, 1), firing(1.0 + kTau, 2, 2)}, true);
  EXPECT_EQ(fates(log), (std::vector<Fate>{Fate::Delivered, Fate::Delivered}));
}

TEST_F(EventBusTest, ChainOfThreeIsLostWholeThoughTheEndsAreFarApart) {
  // A-B and B-C overlap; A and C are 1.6 tau apart yet both hit B's transmission.
  EventLog log = aloha({firing(1.0, 1, 1), firing(1.0 + 0.8 * kTau, 2, 2), firing(1.0 + 1.6 * kTau, 3, 3),
                        firing(1.0 + 3.0 * kTau, 4, 4)},
                       true);
  EXPECT_EQ(fates(log), (std::vector<Fate>{Fate::Collided, Fate::Collided, Fate::Collided, Fate::Delivered}));
  EXPECT_EQ(log.totals().fired, 4u);
  EXPECT_EQ(log.totals().delivered, 1u);
}

TEST_F(EventBusTest, WithoutContentionDetectionTheReceiverGetsTheOrAsAGhost) {
  // (x=1, y=2) is bus address (2 << 5) | 1 = 0b00010'00001; (x=4, y=8) is 0b01000'00100.
  // OR = 0b01010'00101: the pixel (5, 10), which never fired.
  EventLog log = aloha({firing(1.0, 1, 2), firing(1.2, 4, 8)}, false);
  EXPECT_EQ(fates(log), (std::vector<Fate>{Fate::Ghost, Fate::Ghost}));
  ASSERT_EQ(log.events().size(), 1u);
  const AddressEvent& g = log.events()[0];
  EXPECT_EQ(g.bus_address, (10u << 5) | 5u);
  EXPECT_EQ(g.x, 5u);
  EXPECT_EQ(g.y, 10u);
  EXPECT_EQ(g.flags, kGhostEvent);
  EXPECT_EQ(g.t, 1.0);  // latched at the start of the busy period
  const TileCounters c = log.totals();
  EXPECT_EQ(c.collided, 2u);
  EXPECT_EQ(c.ghost, 1u);
  EXPECT_EQ(c.delivered, 1u);  // the ghost reached the output
}

// The bus takes a tile's firings in batches (the event rung hands over 256 at a time) and finds
// the clusters within a batch in place. Whatever the batch boundaries, each firing's fate must be
// pure ALOHA's, computed here from scratch: a firing is lost iff another starts within tau of it,
// and the firings so linked form a cluster, which leaves one ghost (the OR of its addresses, at
// its first start) when the receiver cannot detect the collision.
TEST_F(EventBusTest, BatchesOfAnySizeGiveEachFiringPureAlohasFate) {
  std::mt19937_64 rng(7);
  std::vector<AddressEvent> firings;
  double t = 0;
  for (int i = 0; i < 3000; ++i) {
    // Gaps around tau, some zero (simultaneous firings), so that clusters of every size occur
    // and straddle batch boundaries.
    const int kind = static_cast<int>(rng() % 8);
    t += kind == 0 ? 0.0 : kTau * 0.3 * static_cast<double>(rng() % 10);
    firings.push_back(firing(t, static_cast<std::uint32_t>(rng() % 32), static_cast<std::uint32_t>(rng() % 32)));
  }
  for (const bool detect : {true, false}) {
    // Pure ALOHA from scratch: clusters chain firings less than tau after the previous one.
    std::vector<Fate> expected(firings.size(), Fate::Delivered);
    std::vector<AddressEvent> expected_out;
    for (std::size_t a = 0; a < firings.size();) {
      std::size_t b = a + 1;
      while (b < firings.size() && firings[b].t - firings[b - 1].t < kTau) ++b;
      if (b - a == 1) {
        expected_out.push_back(firings[a]);
      } else {
        std::uint32_t address = 0;
        for (std::size_t k = a; k < b; ++k) {
          expected[k] = detect ? Fate::Collided : Fate::Ghost;
          address |= firings[k].bus_address;
        }
        if (!detect) {
          AddressEvent ghost = firings[a];
          ghost.bus_address = address;
          ghost.x = address & 31;
          ghost.y = address >> 5;
          ghost.flags = kGhostEvent;
          expected_out.push_back(ghost);
        }
      }
      a = b;
    }
    // Both fates common, collisions of two and of many.
    ASSERT_GT(std::count(expected.begin(), expected.end(), Fate::Delivered), 300);
    ASSERT_GT(std::count(expected.begin(), expected.end(), detect ? Fate::Collided : Fate::Ghost), 300);
    for (const std::size_t most : {std::size_t(1), std::size_t(2), std::size_t(7), std::size_t(256), firings.size()}) {
      EventLog log(1, true);
      const AddressMap map(array_);
      AlohaBus bus(log, map, kTau, detect);
      std::mt19937_64 sizes(most);
      for (std::size_t at = 0; at < firings.size();) {
        const std::size_t n = std::min(firings.size() - at, 1 + static_cast<std::size_t>(sizes() % most));
        bus.request_all(firings.data() + at, n);
        at += n;
      }
      bus.finish();
      log.finish();
      ASSERT_EQ(fates(log), expected) << "batches of up to " << most << ", detect " << detect;
      ASSERT_EQ(log.events().size(), expected_out.size());
      for (std::size_t k = 0; k < expected_out.size(); ++k) {
        const AddressEvent& got = log.events()[k];
        EXPECT_EQ(got.t, expected_out[k].t);
        EXPECT_EQ(got.bus_address, expected_out[k].bus_address);
        EXPECT_EQ(got.x, expected_out[k].x);
        EXPECT_EQ(got.y, expected_out[k].y);
        EXPECT_EQ(got.flags, expected_out[k].flags);
      }
      EXPECT_EQ(log.totals().fired, firings.size());
    }
  }
}

TEST_F(EventBusTest, ArbitratedBusServesInFireOrderWithLatency) {
  EventLog log(1, true);
  ArbitratedBus bus(log, kTau, 2.0);
  // Three firings within one tau queue up: starts at 0, tau, 2 tau. A fourth, late, waits for
  // nobody. A fifth arrives when the queue would start it after the end of the run (2 s).
  for (const AddressEvent& f : {firing(0.0, 1, 1), firing(0.1, 2, 2), firing(0.2, 3, 3), firing(1.7, 4, 4),
                                firing(1.75, 5, 5)}) {
    bus.request(f);
  }
  log.finish();
  const auto& t = log.truth();
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[0].t_deliver, 0.0);
  EXPECT_EQ(t[1].t_deliver, 0.5);
  EXPECT_EQ(t[2].t_deliver, 1.0);
  EXPECT_EQ(t[3].t_deliver, 1.7);
  EXPECT_EQ(t[4].fate, Fate::Pending);  // its turn would start at 2.2 s
  ASSERT_EQ(log.events().size(), 4u);
  EXPECT_EQ(log.events()[1].x, 2u);  // fire order kept
  const LatencyStats lat = log.latency();
  EXPECT_DOUBLE_EQ(lat.mean, (0 + 0.4 + 0.8 + 0) / 4);
  EXPECT_DOUBLE_EQ(lat.max, 0.8);
  EXPECT_DOUBLE_EQ(lat.p99, 0.8);
  EXPECT_EQ(log.totals().pending, 1u);
}

}  // namespace
}  // namespace aesim
