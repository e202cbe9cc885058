#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <vector>

#include <systemc>

#include "aesim/embed/imager.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/events/event_log.hpp"

namespace aesim {

// sc_fifo<AddressEvent> prints its contents with this (SystemC requires it of a FIFO's type).
std::ostream& operator<<(std::ostream& out, const AddressEvent& e);

// The imager at the event fidelity (the exact event rung, the fastest) as a SystemC module for
// the caller's own sc_main: the events the receivers deliver, each handed over at its delivery
// time in the caller's simulation (SystemC time, 1 ps resolution), to whatever the `out` port is
// bound to (an sc_fifo<AddressEvent>: a full FIFO holds the source back, so a consumer that
// falls behind sees later times, as a real one would) and to the callback set with on_event().
// The run is simulated when the module is built (in plain C++, outside any SystemC context), so
// its events are in memory: sim.max_events bounds them as it bounds any run.
//
// The same preset, scene and settings give the events of `aesim run --set sim.fidelity=event`.
// Bad input throws InputError from the constructor, as Imager's does; `ImagerSpec::receiver` has
// no meaning here (the event rung has no clocked receiver) and is refused.
class EventSource : public sc_core::sc_module {
 public:
  // Zero or one FIFO: unbound, the events go to the callback only (with neither, the module only
  // holds the run: events(), as EventFifoTarget::deliver takes it).
  sc_core::sc_port<sc_core::sc_fifo_out_if<AddressEvent>, 1, sc_core::SC_ZERO_OR_MORE_BOUND> out;

  EventSource(const sc_core::sc_module_name& name, const ImagerSpec& spec);
  ~EventSource() override;
  SC_HAS_PROCESS(EventSource);

  // Called with each event at its delivery time (before it is written to `out`).
  void on_event(std::function<void(const AddressEvent&)> callback) { callback_ = std::move(callback); }

  const ResolvedConfig& config() const;
  double tick() const;
  // The whole run, known from the start: every event and each tile's counters.
  const std::vector<AddressEvent>& events() const;
  std::vector<TileCounters> tiles() const;

 private:
  struct Run;
  std::unique_ptr<Run> run_;
  std::function<void(const AddressEvent&)> callback_;
  void emit();
};

}  // namespace aesim
