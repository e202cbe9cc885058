#pragma once
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace aesim {

// A fixed set of threads that run one loop at a time, `for_each(n, fn)`: fn(i) for every i in
// [0, n), indices handed out one at a time, the calling thread working too. Cheap enough to run
// thousands of short loops (a window of a run each) without starting threads per loop.
class WorkerPool {
 public:
  // `threads` in all, the caller included (1: no extra thread).
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Threads in all, the caller included.
  int threads() const { return static_cast<int>(threads_.size()) + 1; }
  // Returns when every fn(i) has returned; rethrows the first exception one threw (the others'
  // indices still run). Indices are handed out in order: 0 starts first.
  void for_each(std::size_t n, const std::function<void(std::size_t)>& fn);

 private:
  void work();
  void run_items();

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(std::size_t)>* fn_ = nullptr;
  std::size_t n_ = 0;
  std::atomic<std::size_t> next_{0};
  std::size_t generation_ = 0;
  int running_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace aesim
