#pragma once
#include <cstddef>
#include <vector>

#include "events/event_stream.hpp"

namespace aesim {

// Each tile's records since the last hand-over, in the order the tile produced them.
struct TileRecords {
  explicit TileRecords(std::size_t tiles = 0) : events(tiles), truth(tiles) {}
  std::vector<std::vector<AddressEvent>> events;
  std::vector<std::vector<TruthRecord>> truth;
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
  std::vector<std::vector<AddressEvent>> events_;  // held: not yet earlier than a `before`
  std::vector<std::vector<TruthRecord>> truth_;
  std::vector<AddressEvent> event_chunk_;
  std::vector<TruthRecord> truth_chunk_;
  EventStream& out_;
};

}  // namespace aesim
