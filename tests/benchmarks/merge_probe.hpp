#pragma once
#include <cstdint>
#include <vector>

#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_merger.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// The tiles' records of a run as the event log hands them to the merge: per window, each tile's
// records in the order it produced them, and the time before which the window's records are final.
struct RecordedWindows {
  std::vector<TileRecords> windows;
  std::vector<double> before;
  std::size_t events = 0;
};

// A run's delivered events cut into `windows` windows of equal counts.
RecordedWindows record_windows(const ResolvedConfig& config, const Photocurrents& photocurrents, std::size_t windows);

// The least work a merge of the tiles' sorted streams must do by comparisons: a k-way merge (a tree
// of losers over the tiles' next records, keyed by time, tile and address) into 8-byte records (a
// microsecond stamp and a bus address), appended to a cache-resident buffer. Returns the records
// made.
std::uint64_t merge_probe(const RecordedWindows& recorded);

}  // namespace aesim
