#pragma once
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "aesim/threads/serial_worker.hpp"

namespace aesim {

// Full buffers handed to a job on a thread of its own while the caller fills the next: a writer's
// buffers written into the page cache beside the merge (a seventh of the merge thread's time writing
// AEDAT 2.0 at QCIF), the tiles' window records merged and written beside the tiles. Buffers go
// round (one at its job, one waiting, one filling), so none is allocated and grown anew: each comes
// back as its job left it (capacity kept). The thread starts with the first hand-over, so an output
// of less than one buffer never has one. A job's error is rethrown by the next post() or by drain(),
// and the jobs after it are skipped. Destroyed without drain() (a run that failed), the job under
// way finishes and the rest are dropped.
template <typename Buffer>
class BufferHandOff {
 public:
  // `fresh()` makes a buffer for the caller while none has come back yet.
  explicit BufferHandOff(std::function<Buffer()> fresh = [] { return Buffer(); }) : fresh_(std::move(fresh)) {}

  // Waits while one buffer waits, then hands `filled` to `job` (run on the thread, in the order
  // handed over) and puts in its place a buffer a job is done with or, the first times, fresh().
  // Refused (an earlier job failed), `filled` stays with the caller as it was.
  template <typename Job>
  void post(Buffer& filled, Job job) {
    if (!worker_) worker_ = std::make_unique<SerialWorker>(1);
    auto full = std::make_shared<Buffer>(std::move(filled));
    try {
      worker_->post([this, full, job = std::move(job)] {
        job(*full);
        std::lock_guard<std::mutex> lock(spare_mutex_);
        spare_.push_back(std::move(*full));
      });
    } catch (...) {
      filled = std::move(*full);
      throw;
    }
    std::lock_guard<std::mutex> lock(spare_mutex_);
    if (spare_.empty()) {
      filled = fresh_();
    } else {
      filled = std::move(spare_.back());
      spare_.pop_back();
    }
  }
  // Waits until every buffer handed over has been through its job; rethrows a job's error.
  void drain() {
    if (worker_) worker_->drain();
  }

 private:
  std::function<Buffer()> fresh_;
  std::mutex spare_mutex_;
  std::vector<Buffer> spare_;
  std::unique_ptr<SerialWorker> worker_;  // last: its jobs use the members above
};

}  // namespace aesim
