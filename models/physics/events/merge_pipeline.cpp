#include "aesim/events/merge_pipeline.hpp"

#include "aesim/threads/thread_placement.hpp"

namespace aesim {

MergePipeline::MergePipeline(EventMerger& merger, std::size_t tiles)
    : merger_(merger), batch_(tiles), thread_(start_off_callers_cpu([this] { work(); })) {}

MergePipeline::~MergePipeline() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void MergePipeline::wait_idle(std::unique_lock<std::mutex>& lock) {
  changed_.wait(lock, [this] { return !busy_; });
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

void MergePipeline::submit(TileRecords& filled, double before) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    wait_idle(lock);
    std::swap(batch_, filled);
    before_ = before;
    busy_ = true;
  }
  changed_.notify_all();
}

void MergePipeline::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  wait_idle(lock);
}

void MergePipeline::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return busy_ || stop_; });
    if (!busy_) return;
    lock.unlock();
    std::exception_ptr error;
    try {
      merger_.merge(batch_, before_);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    // After an error the rest of the run's records are discarded: the run fails and writes nothing.
    if (error && !error_) error_ = error;
    busy_ = false;
    changed_.notify_all();
  }
}

}  // namespace aesim
