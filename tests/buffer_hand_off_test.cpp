// BufferHandOff runs a job on each full buffer on a thread of its own (AEDAT 2.0's writes, the
// event log's merges): every buffer once, in order, with the bytes it was handed; three buffers
// going round; a job's error back to the caller, with no job after it run. And the AEDAT 2.0 writer
// through it: the same bytes as the records written at once, over many buffers, and a failing
// stream left failed.
#include <gtest/gtest.h>

#include <future>
#include <set>
#include <sstream>
#include <stdexcept>
#include <streambuf>
#include <vector>

#include "aesim/event_files/aedat.hpp"
#include "aesim/threads/buffer_hand_off.hpp"

namespace aesim {
namespace {

TEST(BufferHandOff, RunsEachBuffersJobOnceInOrderWithThreeGoingRound) {
  std::vector<std::vector<char>> written;
  std::set<const char*> storage;
  BufferHandOff<std::vector<char>> writes;
  std::vector<char> buffer;
  for (int i = 0; i < 2000; ++i) {
    buffer.assign(4096, static_cast<char>(i));
    // A size short of the buffer: only that much is written.
    const auto size = static_cast<std::ptrdiff_t>(1 + i % 4096);
    writes.post(buffer, [&, size](const std::vector<char>& full) {
      written.emplace_back(full.begin(), full.begin() + size);
      storage.insert(full.data());
    });
  }
  writes.drain();
  ASSERT_EQ(written.size(), 2000u);
  for (int i = 0; i < 2000; ++i) {
    const std::vector<char>& w = written[static_cast<std::size_t>(i)];
    ASSERT_EQ(w.size(), static_cast<std::size_t>(1 + i % 4096)) << i;
    ASSERT_EQ(w.front(), static_cast<char>(i)) << i;
    ASSERT_EQ(w.back(), static_cast<char>(i)) << i;
  }
  // One written, one waiting, one being filled: assign() into a buffer given back reuses its
  // storage, so no more than three are ever made.
  EXPECT_LE(storage.size(), 3u);
}

TEST(BufferHandOff, AJobsErrorComesBackAndNoJobAfterItRuns) {
  int wrote = 0;
  BufferHandOff<std::vector<char>> writes;
  const auto write = [&](const std::vector<char>&) {
    if (wrote == 5) throw std::runtime_error("No space left on device");
    ++wrote;
  };
  bool thrown = false;
  try {
    std::vector<char> buffer(16);
    for (int i = 0; i < 100; ++i) writes.post(buffer, write);
    writes.drain();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "No space left on device");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(wrote, 5);
  // Refused after the error, a buffer stays with the caller, bytes and all.
  std::vector<char> kept(32, 'k');
  EXPECT_THROW(writes.post(kept, write), std::runtime_error);
  EXPECT_EQ(kept, std::vector<char>(32, 'k'));
}

TEST(BufferHandOff, TheCallerGetsABufferAJobLeftOrAFreshOne) {
  // The event log's batches: a fresh one has a vector a tile, a merged one comes back emptied.
  BufferHandOff<std::vector<int>> merges([] { return std::vector<int>(3, -1); });
  std::vector<int> batch(10, -2);
  // The first job holds on until the caller has looked at what it got back: nothing had come back.
  std::promise<void> go;
  const std::shared_future<void> going = go.get_future().share();
  merges.post(batch, [going](std::vector<int>& b) {
    going.wait();
    b.assign(1, 42);
  });
  EXPECT_EQ(batch, std::vector<int>(3, -1));
  go.set_value();
  int fresh = 1;
  for (int i = 0; i < 500; ++i) {
    batch.assign(10, i);
    merges.post(batch, [](std::vector<int>& b) { b.assign(1, 42); });
    ASSERT_TRUE(batch == std::vector<int>(3, -1) || batch == std::vector<int>(1, 42)) << i;
    fresh += batch.size() == 3;
  }
  merges.drain();
  // One at its job, one waiting, one with the caller: no more than three were ever made.
  EXPECT_LE(fresh, 3);
}

// Events over a 64x64 array, a few at each instant, enough for several of the writer's 1 MiB buffers.
std::vector<AddressEvent> many_events(const AddressMap& map, std::size_t n) {
  std::vector<AddressEvent> events(n);
  for (std::size_t i = 0; i < n; ++i) {
    AddressEvent& e = events[i];
    e.t = static_cast<double>(i / 3) * 1e-6;
    e.x = static_cast<int>(i * 7 % 64);
    e.y = static_cast<int>(i * 13 % 64);
    e.tile = static_cast<std::uint32_t>(map.tile_of({e.x, e.y}));
    e.bus_address = map.bus_address({e.x, e.y});
  }
  return events;
}

ArrayParams array_64() {
  ArrayParams a;
  a.rows = a.cols = 64;
  return a;
}

TEST(BufferHandOff, AnAedatWriterWritesTheRecordsBytesOverManyBuffers) {
  const AddressMap map(array_64());
  const std::vector<AddressEvent> events = many_events(map, 600'000);  // 4.8 MB of records
  const std::vector<std::string> header = aedat_header(map, {});
  std::ostringstream at_once;
  write_aedat(at_once, header, aedat_records(events, map, 1e-6));
  std::ostringstream streamed;
  AedatWriter writer(streamed, header, map, 1e-6);
  // One call of more than two buffers' records (131,072 a buffer), then calls of a few thousand.
  writer.events(events.data(), 300'000);
  for (std::size_t at = 300'000; at < events.size(); at += 4999) {
    writer.events(events.data() + at, std::min<std::size_t>(4999, events.size() - at));
  }
  writer.finish();
  // finish() returns with every byte in the stream, before the writer is gone.
  const std::string got = streamed.str(), expected = at_once.str();
  EXPECT_TRUE(got == expected) << got.size() << " bytes written, " << expected.size() << " expected";
}

// Takes `room` bytes, then fails every write.
class FillingBuffer : public std::streambuf {
 public:
  explicit FillingBuffer(std::size_t room) : room_(room) {}

 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override {
    const auto took = std::min<std::streamsize>(n, static_cast<std::streamsize>(room_));
    room_ -= static_cast<std::size_t>(took);
    return took;
  }
  int_type overflow(int_type c) override { return room_ == 0 ? traits_type::eof() : (--room_, traits_type::not_eof(c)); }

 private:
  std::size_t room_;
};

TEST(BufferHandOff, AnAedatWriterOnAFullDeviceLeavesItsStreamFailed) {
  const AddressMap map(array_64());
  const std::vector<AddressEvent> events = many_events(map, 600'000);
  FillingBuffer full(3 << 20);
  std::ostream out(&full);
  AedatWriter writer(out, aedat_header(map, {}), map, 1e-6);
  writer.events(events.data(), events.size());
  writer.finish();
  EXPECT_TRUE(out.bad());
}

}  // namespace
}  // namespace aesim
