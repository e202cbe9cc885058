// Event-fidelity buses on hand-made cases: pure ALOHA windows, chains, ghosts, arbitration.
#include <gtest/gtest.h>

#include "array/address_map.hpp"
#include "bus/aloha_bus.hpp"
#include "run/imager_simulation.hpp"

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
