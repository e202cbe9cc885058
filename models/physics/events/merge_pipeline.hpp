#pragma once
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "aesim/events/event_merger.hpp"

namespace aesim {

// Merging (and the stream's writing) on a thread of its own, one batch behind the tiles: while the
// tiles simulate window k+1, window k is merged and written. Double buffering: a submitted batch's
// vectors come back, emptied, with the next submit.
class MergePipeline {
 public:
  MergePipeline(EventMerger& merger, std::size_t tiles);
  ~MergePipeline();
  MergePipeline(const MergePipeline&) = delete;
  MergePipeline& operator=(const MergePipeline&) = delete;

  // Waits for the previous batch, then takes `filled` (which gets the previous batch's emptied
  // vectors back) to merge up to `before`. Rethrows an error the previous merge raised.
  void submit(TileRecords& filled, double before);
  // Waits until everything submitted is merged; rethrows an error a merge raised.
  void drain();

 private:
  void work();
  void wait_idle(std::unique_lock<std::mutex>& lock);

  EventMerger& merger_;
  TileRecords batch_;
  double before_ = 0;
  bool busy_ = false, stop_ = false;
  std::exception_ptr error_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::thread thread_;
};

}  // namespace aesim
