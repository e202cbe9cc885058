#pragma once
#include "aesim/bus/event_bus.hpp"
#include "aesim/events/event_log.hpp"

namespace aesim {

// bus.access=ideal: infinite bandwidth, no loss, no delay. Isolates pixel physics.
class IdealBus final : public EventBus {
 public:
  explicit IdealBus(EventLog& log) : log_(log) {}
  void request(const AddressEvent& firing) override { request_all(&firing, 1); }
  void request_all(const AddressEvent* firings, std::size_t n) override {
    log_.fired_and_delivered(firings, n);
  }
  bool delivers_when_fired() const override { return true; }

 private:
  EventLog& log_;
};

}  // namespace aesim
