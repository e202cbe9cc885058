#include "events/event_merger.hpp"

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
constexpr std::size_t kAhead = 8;      // records prefetched ahead in each tile's buffer

// Merges every tile's records earlier than `before` through a tree of losers over the tiles'
// heads into `chunk`, passing full chunks to `emit`. A tile's records are those it held back last
// time followed by its new ones; in the event rung both are in order and the new ones come later,
// so they are read where they lie, and only what stays for the next window is copied (the tail
// past `before`), which keeps the buffers to the two sets the tiles and the merge swap. Otherwise
// (simultaneous SystemC processes may have run in any order) they are joined and sorted; a
// stable sort keeps production order among equal keys, as a sort of the whole run would.
template <typename T, typename Out, typename Emit>
void merge_window(std::vector<std::vector<T>>& incoming, std::vector<std::vector<T>>& held, double before,
                  std::vector<Out>& chunk, Emit emit) {
  // Within one tile's records (the tile part of the key is the same).
  auto less = [](const T& a, const T& b) { return before_in_tile(a, b); };
  auto early = [before](const T& r) { return time_of(r) < before; };
  const std::size_t tiles = held.size();
  // A tile's records to merge: [a, a_end) then [b, b_end).
  struct Cursor {
    const T *a, *a_end, *b, *b_end;
    // The records were written on the tiles' core and wait in the shared cache: with many tiles
    // interleaved, the hardware prefetcher loses track of them, so each read asks for the
    // records a few lines ahead of it.
    const T& next() {
      const T*& p = a != a_end ? a : b;
      __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(p) + kAhead * sizeof(T)));
      return *p++;
    }
    bool done() const { return a == a_end && b == b_end; }
    const T& peek() const { return a != a_end ? *a : *b; }
  };
  std::vector<Cursor> cursor(tiles);
  std::vector<std::size_t> from_held(tiles, 0), from_new(tiles, 0);
  // A tree of losers over the tiles' heads: each inner node keeps the tile that lost the match
  // there, so a pop replays only the winner's path, one comparison (and one key read) a level,
  // with no records moved (a heap compares twice a level and moves its entries; a tree of
  // winners reads both children).
  std::size_t leaves = 1;
  while (leaves < tiles) leaves *= 2;
  const OrderKey exhausted = ~OrderKey(0);
  std::vector<OrderKey> head(leaves, exhausted);
  std::size_t live = 0;
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
      head[i] = key_of(cursor[i].peek(), static_cast<std::uint32_t>(i));
      live += from_held[i] + from_new[i];
    }
  }
  std::vector<std::uint32_t> winner(2 * leaves), loser(leaves);
  for (std::size_t i = 0; i < leaves; ++i) winner[leaves + i] = static_cast<std::uint32_t>(i);
  for (std::size_t n = leaves - 1; n >= 1; --n) {
    const std::uint32_t l = winner[2 * n], r = winner[2 * n + 1];
    const bool right_wins = head[r] < head[l];
    winner[n] = right_wins ? r : l;
    loser[n] = right_wins ? l : r;
  }
  std::uint32_t w = winner[1];
  std::size_t used = 0;
  for (; live > 0; --live) {
    Cursor& c = cursor[w];
    put(chunk[used], c.next(), w);
    if (++used == kChunk) {
      emit(chunk.data(), used);
      used = 0;
    }
    OrderKey climbing = c.done() ? exhausted : key_of(c.peek(), w);
    head[w] = climbing;
    // Which side wins is as good as random, so the swap is done with masks: written as selects,
    // GCC compiled it to a branch, mispredicted at every other level, 80 % of the merge's time in
    // perf. The path's nodes and their losers do not depend on the matches, so they load early;
    // what each level waits for is the comparison below it.
    for (std::size_t n = (leaves + w) / 2; n >= 1; n /= 2) {
      const std::uint32_t l = loser[n];
      const OrderKey other = head[l];
      const std::uint64_t swap = std::uint64_t(0) - static_cast<std::uint64_t>(other < climbing);
      const std::uint32_t flip = (l ^ w) & static_cast<std::uint32_t>(swap);
      loser[n] = l ^ flip;
      w ^= flip;
      climbing ^= (climbing ^ other) & ((OrderKey(swap) << 64) | swap);
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
  merge_window(batch.events, events_, before, event_chunk_,
               [this](const AddressEvent* c, std::size_t n) { out_.events(c, n); });
  merge_window(batch.truth, truth_, before, truth_chunk_,
               [this](const TruthRecord* c, std::size_t n) { out_.truth(c, n); });
}

}  // namespace aesim
