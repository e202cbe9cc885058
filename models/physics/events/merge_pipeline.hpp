#pragma once
#include <mutex>
#include <vector>

#include "aesim/events/event_merger.hpp"
#include "aesim/threads/serial_worker.hpp"

namespace aesim {

// Merging (and the stream's writing) on a thread of its own (a SerialWorker), behind the tiles:
// while the tiles simulate window k+2, window k is merged and written and window k+1 waits, so that
// a window the tiles finish quickly does not make them wait for a slow merge, nor the merge for the
// tiles, as long as the two keep pace on average (bright QCIF to .aedat4: 39 -> 44 M events/s
// against one window at a time), for a third window's records in memory. A submitted batch's
// vectors come back, emptied, with a later submit.
class MergePipeline {
 public:
  MergePipeline(EventMerger& merger, std::size_t tiles);

  // Waits while a batch waits, then takes `filled` (which gets an emptied batch's vectors back) to
  // merge up to `before`. Rethrows an error an earlier merge raised.
  void submit(TileRecords& filled, double before);
  // Waits until everything submitted is merged; rethrows an error a merge raised.
  void drain();

 private:
  EventMerger& merger_;
  std::size_t tiles_;
  std::mutex emptied_mutex_;
  std::vector<TileRecords> emptied_;  // merged, their vectors' capacity kept for the tiles
  SerialWorker worker_;  // last: its jobs use the members above, so it stops first
};

}  // namespace aesim
