#pragma once
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "aesim/events/event_merger.hpp"

namespace aesim {

// Merging (and the stream's writing) on a thread of its own, behind the tiles: while the tiles
// simulate window k+2, windows k and k+1 wait or are merged and written. Two batches may wait, so
// that a window the tiles finish quickly does not make them wait for a slow merge, nor the merge
// for the tiles, as long as the two keep pace on average (bright QCIF to .aedat4: 39 -> 44 M
// events/s), for a third window's records in memory. A submitted batch's vectors come back,
// emptied, with a later submit.
class MergePipeline {
 public:
  MergePipeline(EventMerger& merger, std::size_t tiles);
  ~MergePipeline();
  MergePipeline(const MergePipeline&) = delete;
  MergePipeline& operator=(const MergePipeline&) = delete;

  // Waits while kWaiting batches wait, then takes `filled` (which gets an emptied batch's vectors
  // back) to merge up to `before`. Rethrows an error an earlier merge raised.
  void submit(TileRecords& filled, double before);
  // Waits until everything submitted is merged; rethrows an error a merge raised.
  void drain();

  static constexpr std::size_t kWaiting = 2;

 private:
  struct Batch {
    TileRecords records;
    double before;
  };
  void work();
  void rethrow(std::unique_lock<std::mutex>& lock);

  EventMerger& merger_;
  std::deque<Batch> waiting_;          // submitted, in order; the front one is being merged while busy_
  std::vector<TileRecords> emptied_;   // merged, their vectors' capacity kept for the tiles
  bool busy_ = false, stop_ = false;
  std::exception_ptr error_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::thread thread_;
};

}  // namespace aesim
