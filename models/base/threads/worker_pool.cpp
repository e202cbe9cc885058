#include "aesim/threads/worker_pool.hpp"

#include "aesim/threads/thread_placement.hpp"

namespace aesim {

WorkerPool::WorkerPool(int threads) {
  for (int i = 1; i < threads; ++i) threads_.push_back(start_off_callers_cpu([this] { work(); }));
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void WorkerPool::run_items() {
  for (std::size_t i = next_++; i < n_; i = next_++) {
    try {
      (*fn_)(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
}

void WorkerPool::for_each(std::size_t n, const std::function<void(std::size_t)>& fn) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    fn_ = &fn;
    n_ = n;
    next_ = 0;
    running_ = static_cast<int>(threads_.size());
    ++generation_;
  }
  start_.notify_all();
  run_items();
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return running_ == 0; });
  fn_ = nullptr;
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

void WorkerPool::work() {
  std::size_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    start_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    lock.unlock();
    run_items();
    lock.lock();
    if (--running_ == 0) done_.notify_all();
  }
}

}  // namespace aesim
