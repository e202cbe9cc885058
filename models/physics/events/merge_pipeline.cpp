#include "aesim/events/merge_pipeline.hpp"

#include <utility>

#include "aesim/threads/thread_placement.hpp"

namespace aesim {

MergePipeline::MergePipeline(EventMerger& merger, std::size_t tiles)
    : merger_(merger), thread_(start_off_callers_cpu([this] { work(); })) {
  for (std::size_t i = 0; i < kWaiting; ++i) emptied_.emplace_back(tiles);
}

MergePipeline::~MergePipeline() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void MergePipeline::rethrow(std::unique_lock<std::mutex>&) {
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

void MergePipeline::submit(TileRecords& filled, double before) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !emptied_.empty() || error_; });
    rethrow(lock);
    TileRecords spare = std::move(emptied_.back());
    emptied_.pop_back();
    std::swap(spare, filled);
    waiting_.push_back({std::move(spare), before});
  }
  changed_.notify_all();
}

void MergePipeline::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return (waiting_.empty() && !busy_) || error_; });
  rethrow(lock);
}

void MergePipeline::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return !waiting_.empty() || stop_; });
    if (waiting_.empty()) return;
    busy_ = true;
    Batch& batch = waiting_.front();
    lock.unlock();
    std::exception_ptr error;
    try {
      merger_.merge(batch.records, batch.before);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    // After an error the rest of the run's records are discarded: the run fails and writes nothing.
    if (error && !error_) error_ = error;
    emptied_.push_back(std::move(batch.records));
    waiting_.pop_front();
    if (error_) {
      for (Batch& b : waiting_) emptied_.push_back(std::move(b.records));
      waiting_.clear();
    }
    busy_ = false;
    changed_.notify_all();
  }
}

}  // namespace aesim
