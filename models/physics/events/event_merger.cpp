#include "aesim/events/event_merger.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace aesim {
namespace {

// (time, tile, address) as one unsigned 128-bit number: the time's bits above tile << 32 | bus
// address. Record times are never negative or NaN, and the bits of non-negative doubles order as
// the doubles do (adding +0.0 turns a -0.0 into +0.0), so the number orders records exactly as
// the triple does, in one integer comparison where two floating-point ones and their NaN checks
// sat on the merge's critical path: each level of the tree waits for the one below.
using OrderKey = unsigned __int128;
OrderKey order_key(double t, std::uint64_t rest) {
  std::uint64_t bits;
  const double normal = t + 0.0;
  std::memcpy(&bits, &normal, sizeof bits);
  return (OrderKey(bits) << 64) | rest;
}
OrderKey key_of(const AddressEvent& e) { return order_key(e.t, (std::uint64_t(e.tile) << 32) | e.bus_address); }
// A buffered record of tile `tile` (TruthRecords name their tile themselves).
OrderKey key_of(const TileEvent& e, std::uint32_t tile) {
  return order_key(e.t, (std::uint64_t(tile) << 32) | (e.address_ghost & ~TileEvent::kGhostBit));
}
OrderKey key_of(const TruthRecord& r, std::uint32_t) { return key_of(r.firing); }
double time_of(const TileEvent& e) { return e.t; }
double time_of(const TruthRecord& r) { return r.firing.t; }
void put(AddressEvent& out, const TileEvent& e, std::uint32_t tile) { e.expand(tile, out); }
void put(TruthRecord& out, const TruthRecord& r, std::uint32_t) { out = r; }
// Within one tile's records: the time first, the whole key only for equal times (this runs over
// every record of every window).
bool before_in_tile(const TileEvent& a, const TileEvent& b) {
  return a.t < b.t || (a.t == b.t && (a.address_ghost & ~TileEvent::kGhostBit) < (b.address_ghost & ~TileEvent::kGhostBit));
}
bool before_in_tile(const TruthRecord& a, const TruthRecord& b) { return key_of(a, 0) < key_of(b, 0); }

constexpr std::size_t kChunk = 4096;  // records per call of the stream: a few pages, cache-resident
// Records sorted at a time: a slice of the window's time holding about this many, gathered from
// every tile, sorted by a counting sort on time and passed on. Two buffers of them (32 bytes a
// record) stay in the core's own cache.
constexpr std::size_t kSlice = 4096;
// A bucket of the slice's counting sort holding more records than this (many firings at one
// instant) is sorted by a merge sort rather than by insertion.
constexpr std::size_t kInsertionMost = 16;

double time_of_key(OrderKey key) {
  const auto bits = static_cast<std::uint64_t>(key >> 64);
  double t;
  std::memcpy(&t, &bits, sizeof t);
  return t;
}

// Merges every tile's records earlier than `before` into `chunk`, passing full chunks to `emit`.
// A tile's records are those it held back last time followed by its new ones; in the event rung
// both are in order and the new ones come later, so they are read where they lie, and only what
// stays for the next window is copied (the tail past `before`), which keeps the buffers to the two
// sets the tiles and the merge swap. Otherwise (simultaneous SystemC processes may have run in any
// order) they are joined and sorted; a stable sort keeps production order among equal keys, as a
// sort of the whole run would.
//
// The window's span of time is cut into slices of about kSlice records. Each slice takes every
// tile's records in it (each tile's in order, so a slice is a prefix of what is left of each) and
// counting-sorts them on time into about a bucket a record, then orders each bucket by the whole
// key (time, tile, address), keeping production order among equal keys. A record costs the same
// whatever the number of tiles, where a k-way merge pays log2(tiles) comparisons for it.
template <typename T, typename Out, typename Emit>
void merge_window(std::vector<std::vector<T>>& incoming, std::vector<std::vector<T>>& held, double before,
                  std::vector<Out>& chunk, MergeScratch<T>& scratch, Emit emit) {
  // Within one tile's records (the tile part of the key is the same).
  auto less = [](const T& a, const T& b) { return before_in_tile(a, b); };
  auto early = [before](const T& r) { return time_of(r) < before; };
  const std::size_t tiles = held.size();
  // A tile's records to merge: [a, a_end) then [b, b_end).
  struct Cursor {
    const T *a, *a_end, *b, *b_end;
    bool done() const { return a == a_end && b == b_end; }
    const T& peek() const { return a != a_end ? *a : *b; }
    const T& last() const { return b != b_end ? b_end[-1] : a_end[-1]; }
    void skip() { (a != a_end ? a : b)++; }
  };
  std::vector<Cursor> cursor(tiles);
  std::vector<std::size_t> from_held(tiles, 0), from_new(tiles, 0);
  std::size_t live = 0;
  double t_first = 0, t_last = 0;
  for (std::size_t i = 0; i < tiles; ++i) {
    std::vector<T>& h = held[i];
    std::vector<T>& in = incoming[i];
    const bool in_order = std::is_sorted(in.begin(), in.end(), less) &&
                          (h.empty() || in.empty() || !less(in.front(), h.back()));
    if (!in_order) {
      h.insert(h.end(), in.begin(), in.end());
      in.clear();
      std::stable_sort(h.begin(), h.end(), less);
    }
    from_held[i] = static_cast<std::size_t>(std::partition_point(h.begin(), h.end(), early) - h.begin());
    from_new[i] = from_held[i] < h.size()
                      ? 0
                      : static_cast<std::size_t>(std::partition_point(in.begin(), in.end(), early) - in.begin());
    cursor[i] = {h.data(), h.data() + from_held[i], in.data(), in.data() + from_new[i]};
    if (!cursor[i].done()) {
      const double first = time_of(cursor[i].peek()), last = time_of(cursor[i].last());
      t_first = live == 0 ? first : std::min(t_first, first);
      t_last = live == 0 ? last : std::max(t_last, last);
      live += from_held[i] + from_new[i];
    }
  }
  const std::size_t slices = std::max<std::size_t>(1, live / kSlice);
  const double span = t_last - t_first;
  std::vector<Sorted<T>>& gathered = scratch.gathered;
  std::vector<Sorted<T>>& sorted = scratch.sorted;
  std::vector<std::uint32_t>& count = scratch.count;
  std::size_t used = 0;
  for (std::size_t s = 0; s < slices && live > 0; ++s) {
    // The slice [lo, hi): the last one takes whatever is left.
    const double lo = t_first + span * static_cast<double>(s) / static_cast<double>(slices);
    const bool last_slice = s + 1 == slices;
    const double hi = last_slice ? t_last : t_first + span * static_cast<double>(s + 1) / static_cast<double>(slices);
    gathered.clear();
    for (std::size_t i = 0; i < tiles; ++i) {
      Cursor& c = cursor[i];
      while (!c.done() && (last_slice || time_of(c.peek()) < hi)) {
        gathered.push_back({key_of(c.peek(), static_cast<std::uint32_t>(i)), &c.peek(), static_cast<std::uint32_t>(i)});
        c.skip();
      }
    }
    const std::size_t n = gathered.size();
    live -= n;
    if (n == 0) continue;
    // Buckets of time over [lo, hi], about one a record; (t - lo) * scale never decreases as t
    // grows, so records in a lower bucket come first.
    std::size_t buckets = 1;
    while (buckets < n) buckets *= 2;
    const double width = hi - lo;
    const double scale = width > 0 ? static_cast<double>(buckets) / width : 0;
    const auto bucket_of = [&](OrderKey key) {
      const double b = (time_of_key(key) - lo) * scale;
      return b < static_cast<double>(buckets - 1) ? static_cast<std::size_t>(b) : buckets - 1;
    };
    count.assign(buckets + 1, 0);
    for (const Sorted<T>& g : gathered) ++count[bucket_of(g.key) + 1];
    for (std::size_t b = 0; b < buckets; ++b) count[b + 1] += count[b];
    sorted.resize(n);
    for (const Sorted<T>& g : gathered) sorted[count[bucket_of(g.key)]++] = g;
    // count[b] is now where bucket b ends; each bucket in key order, stably.
    std::size_t begin = 0;
    for (std::size_t b = 0; b < buckets; ++b) {
      const std::size_t end = count[b];
      if (end - begin > kInsertionMost) {
        std::stable_sort(sorted.begin() + static_cast<std::ptrdiff_t>(begin), sorted.begin() + static_cast<std::ptrdiff_t>(end),
                         [](const Sorted<T>& x, const Sorted<T>& y) { return x.key < y.key; });
      } else {
        for (std::size_t k = begin + 1; k < end; ++k) {
          const Sorted<T> moving = sorted[k];
          std::size_t j = k;
          for (; j > begin && moving.key < sorted[j - 1].key; --j) sorted[j] = sorted[j - 1];
          sorted[j] = moving;
        }
      }
      begin = end;
    }
    for (const Sorted<T>& r : sorted) {
      put(chunk[used], *r.record, r.tile);
      if (++used == kChunk) {
        emit(chunk.data(), used);
        used = 0;
      }
    }
  }
  if (used > 0) emit(chunk.data(), used);
  // What stays: the held records from the cut on, then the new ones from theirs.
  for (std::size_t i = 0; i < tiles; ++i) {
    std::vector<T>& h = held[i];
    std::vector<T>& in = incoming[i];
    h.erase(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(from_held[i]));
    h.insert(h.end(), in.begin() + static_cast<std::ptrdiff_t>(from_new[i]), in.end());
    in.clear();
  }
}

}  // namespace

// The chunks are sized here, on the run's thread, even for a run that never merges: sized at the
// first merge, on the merge thread, they made LeakSanitizer's exit-time tracer crash (a read of an
// unmapped page) in four of the six cycle-bus tests, every time.
EventMerger::EventMerger(std::size_t tiles, EventStream& out) : events_(tiles), truth_(tiles), out_(out) {
  event_chunk_.resize(kChunk);
  truth_chunk_.resize(kChunk);
}

void EventMerger::merge(TileRecords& batch, double before) {
  merge_window(batch.events, events_, before, event_chunk_, event_scratch_,
               [this](const AddressEvent* c, std::size_t n) { out_.events(c, n); });
  merge_window(batch.truth, truth_, before, truth_chunk_, truth_scratch_,
               [this](const TruthRecord* c, std::size_t n) { out_.truth(c, n); });
}

}  // namespace aesim
