#include "aesim/events/stream_worker.hpp"

#include "aesim/threads/thread_placement.hpp"

namespace aesim {

StreamWorker::StreamWorker(EventStream& downstream)
    : downstream_(downstream), thread_(start_off_callers_cpu([this] { work(); })) {}

StreamWorker::~StreamWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void StreamWorker::events(const AddressEvent* first, std::size_t count) {
  filling_.events.insert(filling_.events.end(), first, first + count);
  if (filling_.events.size() >= kBlockEvents) hand_over();
}

void StreamWorker::truth(const TruthRecord* first, std::size_t count) {
  filling_.truth.insert(filling_.truth.end(), first, first + count);
  if (filling_.truth.size() >= kBlockEvents) hand_over();
}

void StreamWorker::rethrow_locked() {
  if (error_) std::rethrow_exception(error_);
}

void StreamWorker::hand_over() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < kBlocksInFlight || error_; });
    rethrow_locked();
    queue_.push_back(std::move(filling_));
    filling_ = Block();
    if (!spare_.empty()) {
      filling_ = std::move(spare_.back());
      spare_.pop_back();
    }
  }
  changed_.notify_all();
}

void StreamWorker::drain() {
  if (!filling_.events.empty() || !filling_.truth.empty()) hand_over();
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return (queue_.empty() && !writing_) || error_; });
  rethrow_locked();
}

void StreamWorker::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return !queue_.empty() || stop_; });
    // Stopped before drain(): the run failed, and its writers may be gone; what waits is dropped.
    if (stop_) return;
    Block block = std::move(queue_.front());
    queue_.pop_front();
    writing_ = true;
    const bool failed = error_ != nullptr;
    lock.unlock();
    std::exception_ptr error;
    try {
      if (!failed) {
        if (!block.events.empty()) downstream_.events(block.events.data(), block.events.size());
        if (!block.truth.empty()) downstream_.truth(block.truth.data(), block.truth.size());
      }
    } catch (...) {
      error = std::current_exception();
    }
    block.events.clear();
    block.truth.clear();
    lock.lock();
    if (error && !error_) error_ = error;
    spare_.push_back(std::move(block));
    writing_ = false;
    changed_.notify_all();
  }
}

}  // namespace aesim
