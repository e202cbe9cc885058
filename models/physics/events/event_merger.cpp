#include "aesim/events/event_merger.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

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
OrderKey key_of(const TruthRecord& r) { return key_of(r.firing); }
double time_of(const TileEvent& e) { return e.t; }
double time_of(const AddressEvent& e) { return e.t; }
double time_of(const TruthRecord& r) { return r.firing.t; }
void put(AddressEvent& out, const TileEvent& e, std::uint32_t tile) { e.expand(tile, out); }
void put(TruthRecord& out, const TruthRecord& r, std::uint32_t) { out = r; }
// Within one tile's records: the time first, the whole key only for equal times (this runs over
// every record of every window).
bool before_in_tile(const TileEvent& a, const TileEvent& b) { return a.before(b); }
bool before_in_tile(const TruthRecord& a, const TruthRecord& b) { return key_of(a) < key_of(b); }

// Records sorted at a time: a slice of the window's time holding about this many, from every tile,
// sorted by a counting sort on time and passed on. Their entries (24 bytes an event staged, 32
// placed) and counts stay in the core's own cache.
constexpr std::size_t kSlice = 4096;
constexpr std::size_t kSliceRecordsPerRun = 4;
// A bucket of the slice's counting sort holding more records than this (many firings at one
// instant) is sorted by a merge sort before the insertion pass.
constexpr std::size_t kInsertionMost = 16;
// The tiles' records are read where the tiles wrote them, a window earlier and on another core,
// mostly out of the caches: the copy of a run fetches its lines kPrefetchAhead records on (a run
// gives a QCIF slice about a hundred records, so these are its next slices'), and the first two
// lines of the run kPrefetchRuns on, for thousands of runs giving a slice a few records each
// (merge alone at QCIF 104-116 -> 136-143 M events/s; AEDAT written at 2048x2048 8 % faster).
constexpr std::size_t kPrefetchAhead = 48;
constexpr std::size_t kPrefetchRuns = 8;
template <typename T>
constexpr std::size_t kRecordsPerLine = std::max<std::size_t>(1, 64 / sizeof(T));

// Merges every tile's records earlier than `before`, passing each slice's (below) to `emit` in order.
// A tile's records are those it held back last time followed by its new ones; in the event rung
// both are in order and the new ones come later, so they are read where they lie, and only what
// stays for the next window is copied (the tail past `before`), which keeps the buffers to the two
// sets the tiles and the merge swap. Otherwise (simultaneous SystemC processes may have run in any
// order) they are joined and sorted; a stable sort keeps production order among equal keys, as a
// sort of the whole run would.
//
// The window's span of time is cut into slices of about kSlice records (more with many tiles). A
// slice's records are copied out of the tiles' buffers with their tile, tile after tile, and
// counted into buckets of time (one to two a record of the slice's share of what is left; a slice a
// burst crowds has more records a bucket); then each copy is placed, as the record passed on, at
// its bucket's next free place, so equal keys keep production order. The few buckets that got
// more than one record are put in key order by one insertion pass over the slice
// (a merge sort for a bucket of many records at one instant), and the slice goes on from where it
// was sorted (copying it once more into chunks of a fixed size was a seventh of the merge). A
// record costs the same whatever the number of tiles, where a k-way merge pays log2(tiles)
// comparisons for it; the tiles' buffers are read once, in order: with thousands of tiles, each a
// few records of a slice on a page of its own, reading them where they lay for the placing and
// again for the output missed the TLB on each (the output's read was a seventh of the merge at
// 2048x2048).
//
// `known_in_order`: per tile, nonzero when its incoming records are known to be in order (see
// TileRecords::events_in_order); empty when none is known.
template <typename Buffer, typename Emit>
void merge_window(std::vector<Buffer>& incoming, const std::vector<std::uint8_t>& known_in_order,
                  std::vector<Buffer>& held, double before, MergeScratch& scratch, Emit emit) {
  using T = typename Buffer::value_type;
  using Out = typename Merged<T>::type;
  // Within one tile's records (the tile part of the key is the same).
  auto less = [](const T& a, const T& b) { return before_in_tile(a, b); };
  auto early = [before](const T& r) { return time_of(r) < before; };
  const std::size_t tiles = held.size();
  // The records to merge as runs, each in order: a tile's held ones, then its new ones.
  std::vector<MergeRun<T>>& runs = scratch.of<T>().runs;
  runs.clear();
  std::vector<std::size_t> from_held(tiles, 0), from_new(tiles, 0);
  std::size_t live = 0;
  double t_first = 0, t_last = 0;
  for (std::size_t i = 0; i < tiles; ++i) {
    Buffer& h = held[i];
    Buffer& in = incoming[i];
    const bool in_order = ((i < known_in_order.size() && known_in_order[i]) || std::is_sorted(in.begin(), in.end(), less)) &&
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
    for (const auto& [first, n] : {std::pair<const T*, std::size_t>{h.data(), from_held[i]}, {in.data(), from_new[i]}}) {
      if (n == 0) continue;
      t_first = live == 0 ? time_of(first[0]) : std::min(t_first, time_of(first[0]));
      t_last = live == 0 ? time_of(first[n - 1]) : std::max(t_last, time_of(first[n - 1]));
      live += n;
      runs.push_back({first, first + n, static_cast<std::uint32_t>(i)});
    }
  }
  // Every slice looks at every run once: with thousands of tiles, slices hold a few records a run,
  // so that the look costs less than the records.
  const std::size_t slices = std::max<std::size_t>(1, live / std::max(kSlice, kSliceRecordsPerRun * runs.size()));
  const double span = t_last - t_first;
  std::vector<SliceEntry<T>>& staged = scratch.of<T>().staged;
  std::vector<Out>& sorted = scratch.of<T>().sorted;
  std::vector<std::uint32_t>& count = scratch.count;
  // Order of two records by the whole key (time, tile, address): the time nearly always decides.
  const auto merged_less = [](const Out& a, const Out& b) {
    const double ta = time_of(a), tb = time_of(b);
    if (ta != tb) return ta < tb;
    return key_of(a) < key_of(b);
  };
  for (std::size_t s = 0; s < slices && live > 0; ++s) {
    // The slice [lo, hi): the last one takes whatever is left.
    const double lo = t_first + span * static_cast<double>(s) / static_cast<double>(slices);
    const bool last_slice = s + 1 == slices;
    const double hi = last_slice ? t_last : t_first + span * static_cast<double>(s + 1) / static_cast<double>(slices);
    const double taken_before = last_slice ? std::numeric_limits<double>::infinity() : hi;
    // Buckets of time over [lo, hi], one to two a record of the slice's share of what is left
    // (its count is known only once it is copied; a slice holding more than its share has more
    // records a bucket, and the passes below sort them all the same). (t - lo) * scale never
    // decreases as t grows, so records in a lower bucket come first.
    const std::size_t expected = std::max<std::size_t>(1, live / (slices - s));
    std::size_t buckets = 2;
    while (buckets < expected) buckets *= 2;
    const double width = hi - lo;
    const double scale = width > 0 ? static_cast<double>(buckets) / width : 0;
    const double top = static_cast<double>(buckets - 1);
    const auto bucket_of = [lo, scale, top](double t) {
      const double b = (t - lo) * scale;
      return static_cast<std::uint32_t>(static_cast<std::int64_t>(b < top ? b : top));
    };
    count.assign(buckets + 1, 0);
    // Through a local: the staged records' stores would make the loop reload the vector's data.
    std::uint32_t* const counts = count.data();
    std::uint32_t crowded = 0;  // records in buckets of more than kInsertionMost
    // Each run's records of the slice are copied out, up to its first at or past `hi`: read on
    // from where the slice before stopped, each record's time checked as it is copied (a search
    // for the slice's end in each run first was a sixth of the merge, its steps mispredicted).
    std::size_t n = 0;
    for (std::size_t i = 0; i < runs.size(); ++i) {
      MergeRun<T>& r = runs[i];
      if (i + kPrefetchRuns < runs.size()) {
        const T* ahead = runs[i + kPrefetchRuns].next;
        __builtin_prefetch(ahead);
        __builtin_prefetch(ahead + kRecordsPerLine<T>);
      }
      const T* x = r.next;
      const T* const end = r.end;
      const std::uint32_t tile = r.tile;
      for (;;) {
        // Up to the room made so far: a slice is about kSlice records, while one run may hold a
        // whole run's (a rung that merges once at the end).
        const std::size_t room = staged.size() - n;
        const T* const stop = static_cast<std::size_t>(end - x) > room ? x + room : end;
        SliceEntry<T>* stage = staged.data() + n;
        for (; x != stop && time_of(*x) < taken_before; ++x) {
          __builtin_prefetch(x + kPrefetchAhead);
          const std::uint32_t b = bucket_of(time_of(*x));
          crowded += ++counts[b + 1] > kInsertionMost;
          *stage++ = {*x, tile, b};
        }
        n = static_cast<std::size_t>(stage - staged.data());
        if (x != stop || stop == end || !(time_of(*x) < taken_before)) break;
        staged.resize(std::max(2 * staged.size(), kSlice));
      }
      r.next = x;
    }
    live -= n;
    if (n == 0) continue;
    for (std::size_t b = 0; b < buckets; ++b) counts[b + 1] += counts[b];
    sorted.resize(n);
    Out* const placed = sorted.data();
    for (const SliceEntry<T>* e = staged.data(); e != staged.data() + n; ++e) put(placed[counts[e->bucket]++], e->record, e->tile);
    // counts[b] is now where bucket b ends.
    if (crowded > 0) {
      for (std::size_t b = 0, begin = 0; b < buckets; begin = counts[b++]) {
        if (counts[b] - begin > kInsertionMost) {
          std::stable_sort(sorted.begin() + static_cast<std::ptrdiff_t>(begin),
                           sorted.begin() + static_cast<std::ptrdiff_t>(counts[b]), merged_less);
        }
      }
    }
    // Every record is at most a few places past where it belongs, all within its own bucket.
    for (std::size_t k = 1; k < n; ++k) {
      if (time_of(sorted[k]) > time_of(sorted[k - 1]) || !merged_less(sorted[k], sorted[k - 1])) continue;
      const Out moving = sorted[k];
      std::size_t j = k;
      for (; j > 0 && merged_less(moving, sorted[j - 1]); --j) sorted[j] = sorted[j - 1];
      sorted[j] = moving;
    }
    emit(sorted.data(), n);
  }
  // What stays: the held records from the cut on, then the new ones from theirs.
  for (std::size_t i = 0; i < tiles; ++i) {
    Buffer& h = held[i];
    Buffer& in = incoming[i];
    h.erase(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(from_held[i]));
    h.insert(h.end(), in.begin() + static_cast<std::ptrdiff_t>(from_new[i]), in.end());
    in.clear();
  }
}

}  // namespace

// The sorted slices' room is made here, on the run's thread, even for a run that never merges:
// made at the first merge, on the merge thread, it made LeakSanitizer's exit-time tracer crash (a
// read of an unmapped page) in four of the six cycle-bus tests, every time.
EventMerger::EventMerger(std::size_t tiles, EventStream& out) : events_(tiles), truth_(tiles), out_(out) {
  scratch_.events.sorted.reserve(kSlice);
  scratch_.truth.sorted.reserve(kSlice);
}

void EventMerger::merge(TileRecords& batch, double before) {
  merge_window(batch.events, batch.events_in_order, events_, before, scratch_,
               [this](const AddressEvent* c, std::size_t n) { out_.events(c, n); });
  merge_window(batch.truth, {}, truth_, before, scratch_,
               [this](const TruthRecord* c, std::size_t n) { out_.truth(c, n); });
}

}  // namespace aesim
