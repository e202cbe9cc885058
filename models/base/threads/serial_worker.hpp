#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace aesim {

// Runs jobs one after another on a thread of its own, in the order they were posted, while the
// poster goes on: a writer's compression and system calls beside the merge that feeds it. At most
// `most_waiting` jobs wait, so memory stays bounded whatever the jobs' pace. The first error a job
// raises is rethrown by the next post() or by drain(), and the jobs after it are skipped. Destroyed
// without drain() (a run that failed), it finishes the job running and drops the rest.
class SerialWorker {
 public:
  explicit SerialWorker(std::size_t most_waiting);
  ~SerialWorker();
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  // Waits while `most_waiting` jobs wait; rethrows an earlier job's error.
  void post(std::function<void()> job);
  // Waits until every job posted has run; rethrows a job's error.
  void drain();
  // Jobs posted and not yet started: how far behind the worker is.
  std::size_t waiting();

 private:
  void work();

  std::size_t most_waiting_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> queue_;
  bool running_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once the rest exists
};

}  // namespace aesim
