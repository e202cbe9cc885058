#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "aesim/containers/uninitialized_growth.hpp"
#include "aesim/events/event_stream.hpp"

namespace aesim {

// A receiver's output event while it waits in its tile's buffer for the merge: half an
// AddressEvent, since the window buffers are what a streaming run holds beside its pixels. The
// tile is the buffer's; x and y fit 16 bits (an array is at most 65535 a side); a bus address
// within a tile fits 25 bits (at most 2^24 pixels an array, so ceil(log2 cols) + ceil(log2 rows)
// <= 25), which leaves the top bit for the ghost flag, the only flag there is.
struct TileEvent {
  double t;
  std::uint16_t x, y;
  std::uint32_t address_ghost;

  static constexpr std::uint32_t kGhostBit = 0x80000000u;
  static TileEvent of(const AddressEvent& e) {
    return {e.t, static_cast<std::uint16_t>(e.x), static_cast<std::uint16_t>(e.y),
            e.bus_address | ((e.flags & kGhostEvent) ? kGhostBit : 0u)};
  }
  // Order within a tile's records: time, then bus address. Bitwise, not short-circuit: a loop
  // over a tile's records (the log's check that they come in order) compiles without a branch.
  bool before(const TileEvent& other) const {
    return (t < other.t) | ((t == other.t) & ((address_ghost & ~kGhostBit) < (other.address_ghost & ~kGhostBit)));
  }
  AddressEvent in_tile(std::uint32_t tile) const {
    AddressEvent e;
    expand(tile, e);
    return e;
  }
  // in_tile() written in place, field by field: an event built on the stack and copied whole
  // stalled the merge on store forwarding (narrow stores read back as 16-byte loads).
  void expand(std::uint32_t tile, AddressEvent& e) const {
    e.t = t;
    e.x = x;
    e.y = y;
    e.tile = tile;
    e.bus_address = address_ghost & ~kGhostBit;
    e.flags = (address_ghost & kGhostBit) ? kGhostEvent : kNormalEvent;
  }
};

static_assert(sizeof(TileEvent) == 16, "a buffered event grew");

// Each tile's records since the last hand-over, in the order the tile produced them.
struct TileRecords {
  explicit TileRecords(std::size_t tiles = 0) : events(tiles), truth(tiles), events_in_order(tiles, 0) {}
  std::vector<UninitializedGrowthVector<TileEvent>> events;
  std::vector<std::vector<TruthRecord>> truth;
  // Per tile, nonzero when whoever recorded its events checked, as it went, that each came after
  // the one before (TileEvent::before): the merge then takes them as a sorted run without reading
  // them all once more first (on a large array that read missed the caches: an eighth of the
  // merge). Zero: not known, checked by the merge.
  std::vector<std::uint8_t> events_in_order;
};

// A run of one tile's records, in order, on its way through a merge (event_merger.cpp): the next
// record to merge, its end, its tile.
template <typename T>
struct MergeRun {
  const T *next, *end;
  std::uint32_t tile;
};
// A record copied out of its tile's buffer for a merge's counting sort, with its tile and the
// bucket of time it was counted in (placing it reads the bucket instead of working it out again;
// beside a 16-byte TileEvent and its tile it fills what was padding).
template <typename T>
struct SliceEntry {
  T record;
  std::uint32_t tile;
  std::uint32_t bucket;
};
static_assert(sizeof(SliceEntry<TileEvent>) == 24, "a staged event grew");
// What a merge passes on for a tile's record: an AddressEvent for a TileEvent, a TruthRecord as it is.
template <typename T>
struct Merged {
  using type = T;
};
template <>
struct Merged<TileEvent> {
  using type = AddressEvent;
};
// Where a merge sorts a slice of one kind of record, kept between windows: the runs, the slice's
// records in run order, and the same in time order as they are passed on.
template <typename T>
struct SliceScratch {
  std::vector<MergeRun<T>> runs;
  std::vector<SliceEntry<T>> staged;
  std::vector<typename Merged<T>::type> sorted;
};
struct MergeScratch {
  SliceScratch<TileEvent> events;
  SliceScratch<TruthRecord> truth;
  std::vector<std::uint32_t> count;
  template <typename T>
  SliceScratch<T>& of() {
    if constexpr (std::is_same_v<T, TileEvent>) {
      return events;
    } else {
      return truth;
    }
  }
};

// Merges the tiles' records into one stream, outputs in (time, tile, bus address) order and truth
// in (fire time, tile, bus address) order, a window at a time: a record is passed on once no tile
// can still produce an earlier one. The caller names that time with each batch (`before`); later
// records wait here for the next batch. So the stream's bytes do not depend on the windows, the
// threads, or the order in which simultaneous SystemC processes ran, and nothing waits longer than
// a window.
class EventMerger {
 public:
  EventMerger(std::size_t tiles, EventStream& out);
  // Takes every record of `batch` (leaving its vectors empty, capacity kept for reuse) and passes
  // on those earlier than `before`.
  void merge(TileRecords& batch, double before);

 private:
  std::vector<UninitializedGrowthVector<TileEvent>> events_;  // held: not yet earlier than a `before`
  std::vector<std::vector<TruthRecord>> truth_;
  MergeScratch scratch_;
  EventStream& out_;
};

}  // namespace aesim
