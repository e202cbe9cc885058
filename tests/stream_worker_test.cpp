// StreamWorker hands a compressing writer its records on a thread of its own: every record in
// order across many blocks, a writer's error back to the run (and nothing hangs), and nothing
// written after a run that failed.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "aesim/events/stream_worker.hpp"

namespace aesim {
namespace {

// Keeps what it is given; fails on the `fail_at`-th call of events() when asked to.
class Recording : public EventStream {
 public:
  explicit Recording(int fail_at = -1) : fail_at_(fail_at) {}
  void events(const AddressEvent* first, std::size_t count) override {
    if (++calls_ == fail_at_) throw std::runtime_error("disk full");
    got.insert(got.end(), first, first + count);
  }
  void truth(const TruthRecord* first, std::size_t count) override { truth_got.insert(truth_got.end(), first, first + count); }
  std::vector<AddressEvent> got;
  std::vector<TruthRecord> truth_got;

 private:
  int fail_at_;
  int calls_ = 0;
};

std::vector<AddressEvent> numbered(std::size_t n) {
  std::vector<AddressEvent> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i].t = static_cast<double>(i) * 1e-6;
    v[i].bus_address = static_cast<std::uint32_t>(i);
  }
  return v;
}

TEST(StreamWorker, PassesEveryRecordInOrderAcrossBlocks) {
  Recording out;
  const std::vector<AddressEvent> events = numbered(200000);  // six blocks and a part
  {
    StreamWorker worker(out);
    for (std::size_t at = 0; at < events.size(); at += 777) {
      worker.events(events.data() + at, std::min<std::size_t>(777, events.size() - at));
    }
    TruthRecord r;
    r.firing = events[5];
    worker.truth(&r, 1);
    worker.drain();
    ASSERT_EQ(out.got.size(), events.size());
    for (std::size_t i = 0; i < events.size(); ++i) ASSERT_EQ(out.got[i].bus_address, i) << i;
    ASSERT_EQ(out.truth_got.size(), 1u);
    EXPECT_EQ(out.truth_got[0].firing.bus_address, 5u);
  }
}

TEST(StreamWorker, AWritersErrorReachesTheRunAndNothingHangs) {
  Recording out(2);
  const std::vector<AddressEvent> events = numbered(300000);
  StreamWorker worker(out);
  bool thrown = false;
  try {
    for (std::size_t at = 0; at < events.size(); at += 1000) worker.events(events.data() + at, 1000);
    worker.drain();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "disk full");
  }
  EXPECT_TRUE(thrown);
  // The first block (33 calls of 1000, the first past 2^15) was written before the failing
  // call; nothing after it.
  EXPECT_EQ(out.got.size(), 33000u);
}

TEST(StreamWorker, DestroyedWithoutDrainItWritesNoMore) {
  Recording out;
  const std::vector<AddressEvent> events = numbered(100000);
  {
    StreamWorker worker(out);
    for (std::size_t at = 0; at < events.size(); at += 1000) worker.events(events.data() + at, 1000);
  }
  // Whatever was taken before the destructor, it is a prefix in order, whole blocks of 33 calls;
  // the last thousand, still being filled, was never handed over.
  EXPECT_LE(out.got.size(), 99000u);
  EXPECT_EQ(out.got.size() % 33000, 0u);
  for (std::size_t i = 0; i < out.got.size(); ++i) ASSERT_EQ(out.got[i].bus_address, i) << i;
}

}  // namespace
}  // namespace aesim
