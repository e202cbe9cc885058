#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "aesim/events/event_stream.hpp"

namespace aesim {

// Passes the records it is given to `downstream` (the event file writers) on a thread of its own,
// in the order given, so that the merge goes on while the writers format, compress and write.
// Records are copied into blocks of kBlockEvents; at most kBlocksInFlight wait, so memory stays
// bounded whatever the writers' pace. An error a writer raises is rethrown by the next call
// here (or by drain()), and the records after it are dropped: the run fails and writes nothing.
// Destroyed without drain() (a run that failed), it drops what still waits.
class StreamWorker : public EventStream {
 public:
  explicit StreamWorker(EventStream& downstream);
  ~StreamWorker() override;
  StreamWorker(const StreamWorker&) = delete;
  StreamWorker& operator=(const StreamWorker&) = delete;

  void events(const AddressEvent* first, std::size_t count) override;
  void truth(const TruthRecord* first, std::size_t count) override;
  // Hands over what is still in the block being filled and waits until the writers have taken
  // everything; rethrows a writer's error.
  void drain();

 private:
  struct Block {
    std::vector<AddressEvent> events;
    std::vector<TruthRecord> truth;
  };
  static constexpr std::size_t kBlockEvents = 1 << 15;
  static constexpr std::size_t kBlocksInFlight = 4;

  void hand_over();
  void rethrow_locked();
  void work();

  EventStream& downstream_;
  Block filling_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Block> queue_;
  std::vector<Block> spare_;  // emptied blocks, their capacity kept
  bool writing_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace aesim
