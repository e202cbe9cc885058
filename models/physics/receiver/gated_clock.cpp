#include "aesim/receiver/gated_clock.hpp"

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
  SC_THREAD(run);
}

void GatedClock::run() {
  s_.clk.write(false);
  s_.rst_n.write(true);
  const std::uint64_t p = period_.value();
  const sc_core::sc_time half = sc_core::sc_time::from_value(p / 2);
  for (;;) {
    if (!s_.req.read() && sc_core::sc_time_stamp() >= free_running_until_) wait(s_.req.posedge_event());
    // The first edge strictly after now.
    std::uint64_t k = sc_core::sc_time_stamp().value() / p + 1;
    for (;; ++k) {
      s_.ts.write(static_cast<std::uint32_t>((k / prescale_) & ts_mask_));
      wait(sc_core::sc_time::from_value(k * p) - sc_core::sc_time_stamp());
      s_.clk.write(true);
      ++edges_;
      wait(half);
      s_.clk.write(false);
      const bool may_stop = !s_.req.read() && sc_core::sc_time_stamp() >= free_running_until_ &&
                            (s_.idle.read() || (stop_when_quiet_ && !s_.ack.read()));
      if (may_stop) break;
    }
  }
}

}  // namespace aesim
