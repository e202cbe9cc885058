#pragma once
#include <cstddef>
#include <vector>

#include "aesim/events/address_event.hpp"
#include "aesim/events/truth_record.hpp"

namespace aesim {

// Where a run's records go while it runs, already merged across tiles: the event file writers, or
// a collector that keeps them. Records arrive in chunks of any size (a merge passes each slice of a
// window on as it is sorted), each chunk continuing the last, so a writer needs no more memory
// than its own buffer.
class EventStream {
 public:
  virtual ~EventStream() = default;
  // The receivers' output (delivered and ghost events) in (time, tile, bus address) order.
  virtual void events(const AddressEvent* first, std::size_t count) = 0;
  // Ground truth in (fire time, tile, bus address) order; only when the run keeps truth.
  virtual void truth(const TruthRecord* first, std::size_t count) {
    (void)first;
    (void)count;
  }
};

// An EventStream that keeps everything: for runs whose records are analysed after the run
// (compare, tests, the Python module) rather than written as they come.
class EventCollector : public EventStream {
 public:
  void events(const AddressEvent* first, std::size_t count) override { events_.insert(events_.end(), first, first + count); }
  void truth(const TruthRecord* first, std::size_t count) override { truth_.insert(truth_.end(), first, first + count); }
  const std::vector<AddressEvent>& events() const { return events_; }
  const std::vector<TruthRecord>& truth() const { return truth_; }

 private:
  std::vector<AddressEvent> events_;
  std::vector<TruthRecord> truth_;
};

// Several streams fed the same records (a run writing AEDAT and CSV at once).
class EventStreams : public EventStream {
 public:
  void add(EventStream& stream) { streams_.push_back(&stream); }
  void events(const AddressEvent* first, std::size_t count) override {
    for (EventStream* s : streams_) s->events(first, count);
  }
  void truth(const TruthRecord* first, std::size_t count) override {
    for (EventStream* s : streams_) s->truth(first, count);
  }

 private:
  std::vector<EventStream*> streams_;
};

}  // namespace aesim
