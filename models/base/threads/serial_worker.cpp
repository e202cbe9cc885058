#include "aesim/threads/serial_worker.hpp"

#include "aesim/threads/thread_placement.hpp"

namespace aesim {

SerialWorker::SerialWorker(std::size_t most_waiting)
    : most_waiting_(most_waiting), thread_(start_off_callers_cpu([this] { work(); })) {}

SerialWorker::~SerialWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SerialWorker::post(std::function<void()> job) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < most_waiting_ || error_; });
    if (error_) std::rethrow_exception(error_);
    queue_.push_back(std::move(job));
  }
  changed_.notify_all();
}

void SerialWorker::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return (queue_.empty() && !running_) || error_; });
  if (error_) std::rethrow_exception(error_);
}

std::size_t SerialWorker::waiting() {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

void SerialWorker::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return !queue_.empty() || stop_; });
    // Stopped before drain(): the run failed, and what the jobs write to may be gone.
    if (stop_) return;
    std::function<void()> job = std::move(queue_.front());
    queue_.pop_front();
    running_ = true;
    const bool failed = error_ != nullptr;
    lock.unlock();
    std::exception_ptr error;
    if (!failed) {
      try {
        job();
      } catch (...) {
        error = std::current_exception();
      }
    }
    job = nullptr;
    lock.lock();
    if (error && !error_) error_ = error;
    running_ = false;
    changed_.notify_all();
  }
}

}  // namespace aesim
