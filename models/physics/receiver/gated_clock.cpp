#include "receiver/gated_clock.hpp"

#include <algorithm>

namespace aesim {

GatedClock::GatedClock(const sc_core::sc_module_name& name, ReceiverSignals& s, sc_core::sc_time period,
                       unsigned prescale, int ts_width, sc_core::sc_time free_running_until)
    : sc_module(name),
      s_(s),
      period_(period),
      prescale_(std::max(1u, prescale)),
      ts_mask_(ts_width >= 64 ? ~0ULL : (1ULL << ts_width) - 1),
      free_running_until_(free_running_until) {
  SC_METHOD(step);
}

void GatedClock::schedule_rise(std::uint64_t k) {
  s_.ts.write(static_cast<std::uint32_t>((k / prescale_) & ts_mask_));
  phase_ = Phase::BeforeRise;
  next_trigger(sc_core::sc_time::from_value(k * period_.value()) - sc_core::sc_time_stamp());
}

void GatedClock::step() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  switch (phase_) {
    case Phase::Start:
      s_.clk.write(false);
      s_.rst_n.write(true);
      break;
    case Phase::BeforeRise:
      s_.clk.write(true);
      ++edges_;
      phase_ = Phase::High;
      next_trigger(sc_core::sc_time::from_value(period_.value() / 2));
      return;
    case Phase::High: {
      s_.clk.write(false);
      const bool may_stop = s_.idle.read() && !s_.req.read() && now >= free_running_until_;
      if (!may_stop) {
        // The rising edge after this falling one: k * period with k the edge just past.
        schedule_rise(now.value() / period_.value() + 1);
        return;
      }
      break;
    }
    case Phase::Stopped: break;
  }
  phase_ = Phase::Stopped;
  if (!s_.req.read() && now >= free_running_until_) {
    next_trigger(s_.req.posedge_event());
    return;
  }
  // The first edge strictly after now.
  schedule_rise(now.value() / period_.value() + 1);
}

}  // namespace aesim
