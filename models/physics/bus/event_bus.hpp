#pragma once
#include <cstddef>
#include <limits>

#include "aesim/events/address_event.hpp"

namespace aesim {

// One tile's bus, whatever its model: a firing pixel requests it with its address at the firing
// time, in time order. Plain C++, so that the rungs without SystemC time (event, queue) drive it
// directly; SystemC pixels reach it through a PixelBusPort.
// Aligned to a cache line: the tiles' buses are written on every event, by as many threads as
// tiles run at once, and must not share a line.
class alignas(64) EventBus {
 public:
  virtual ~EventBus() = default;
  virtual void request(const AddressEvent& firing) = 0;
  // Several firings in time order, as request() one after the other: one call a batch for the
  // event rung's hot loop (the buses below run their request() inline).
  virtual void request_all(const AddressEvent* firings, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) request(firings[i]);
  }
  // Whether it delivers every firing at its firing time, through EventLog::fired_and_delivered, or
  // loses it, through EventLog::fired_all, and makes no other output but ghosts: the log may then
  // count a tile's firings per pixel after the run (EventLog::add_firings_later).
  virtual bool delivers_when_fired() const { return false; }
  // After the run: settles what the bus still holds (an undecided collision cluster, a queue).
  virtual void finish() {}
  // The earliest firing it still holds undecided (its outcome, and any output, come later), or
  // infinity: what a streaming run must wait for before passing records on.
  virtual double held_since() const { return std::numeric_limits<double>::infinity(); }
  // Mean duration of a bus transaction as this bus measured it (0 when it has none to measure).
  virtual double measured_tau() const { return 0; }
};

}  // namespace aesim
