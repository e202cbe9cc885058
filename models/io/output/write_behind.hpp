#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "aesim/threads/serial_worker.hpp"

namespace aesim {

// A writer's full buffers written out on a thread of their own while it fills the next: the
// system's copy of each into the page cache (a seventh of the merge thread's time writing AEDAT 2.0
// at QCIF, where that thread sets the pace) runs beside the merge instead of after it. Buffers go
// round (one written, one waiting, one filling), so none is allocated and faulted in anew. The
// thread starts with the first buffer handed over: an output of less than one never has one.
// A write's error is rethrown by the next post() or by drain(). Destroyed without drain() (a run
// that failed), the write under way finishes and the rest are dropped.
template <typename Buffer>
class WriteBehind {
 public:
  // `write(buffer, size)` writes a buffer's first `size` bytes, on the worker's thread, in the order
  // the buffers were handed over; it throws to report a failure.
  explicit WriteBehind(std::function<void(const Buffer&, std::size_t)> write) : write_(std::move(write)) {}

  // Hands `filled` over to be written (its first `size` bytes) and puts in its place a buffer a
  // write is done with (as it was handed over) or, the first times, a new one.
  void post(Buffer& filled, std::size_t size) {
    if (!worker_) worker_ = std::make_unique<SerialWorker>(1);
    auto full = std::make_shared<Buffer>(std::move(filled));
    try {
      worker_->post([this, full, size] {
        write_(*full, size);
        std::lock_guard<std::mutex> lock(spare_mutex_);
        spare_.push_back(std::move(*full));
      });
    } catch (...) {
      // An earlier write failed: the caller keeps its buffer as it was.
      filled = std::move(*full);
      throw;
    }
    std::lock_guard<std::mutex> lock(spare_mutex_);
    if (spare_.empty()) {
      filled = Buffer();
    } else {
      filled = std::move(spare_.back());
      spare_.pop_back();
    }
  }
  // Waits until every buffer handed over is written; rethrows a write's error.
  void drain() {
    if (worker_) worker_->drain();
  }

 private:
  std::function<void(const Buffer&, std::size_t)> write_;
  std::mutex spare_mutex_;
  std::vector<Buffer> spare_;
  std::unique_ptr<SerialWorker> worker_;  // last: its jobs use the members above
};

}  // namespace aesim
