#include "aesim/embed/event_source.hpp"

#include <cmath>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

std::ostream& operator<<(std::ostream& out, const AddressEvent& e) {
  return out << fmt::format("{{t {:.12f} s, x {}, y {}, tile {}, flags {}}}", e.t, e.x, e.y, e.tile, e.flags);
}

struct EventSource::Run {
  ResolvedConfig config;
  SimulationResult result;
};

EventSource::EventSource(const sc_core::sc_module_name& name, const ImagerSpec& spec) : sc_module(name), out("out") {
  if (spec.receiver || !spec.outside_receivers.empty()) throw InputError("EventSource: the event fidelity has no clocked receiver to replace (use Imager)");
  SpecInputs in =
      spec_inputs(spec, Fidelity::Event, "an EventSource is the event fidelity (use Imager for the cycle one)",
                  "aesim/EventSource");
  SimulationResult result = simulate(in.config, in.photocurrents);
  run_.reset(new Run{std::move(in.config), std::move(result)});
  SC_THREAD(emit);
}

EventSource::~EventSource() = default;

const ResolvedConfig& EventSource::config() const { return run_->config; }

double EventSource::tick() const { return run_->result.facts.tick_s; }

const std::vector<AddressEvent>& EventSource::events() const { return run_->result.log.events(); }

std::vector<TileCounters> EventSource::tiles() const { return run_->result.log.tiles(); }

void EventSource::emit() {
  // Delivery times to the caller's time resolution (SystemC's default: 1 ps), from the start of
  // the caller's simulation.
  // Nobody to hand them to (the events taken whole, as EventFifoTarget::deliver takes them): no
  // wake-up per event.
  if (!callback_ && out.size() == 0) return;
  const double step = sc_core::sc_get_time_resolution().to_seconds();
  for (const AddressEvent& e : run_->result.log.events()) {
    const auto at = static_cast<sc_dt::uint64>(std::llround(e.t / step));
    const sc_dt::uint64 now = sc_core::sc_time_stamp().value();
    if (at > now) sc_core::wait(sc_core::sc_time::from_value(at - now));
    if (callback_) callback_(e);
    if (out.size() > 0) out->write(e);
  }
}

}  // namespace aesim
