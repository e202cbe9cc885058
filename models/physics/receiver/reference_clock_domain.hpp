#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <systemc>

#include "aesim/receiver/receiver_cycle_model.hpp"
#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/receiver/stepped_receiver.hpp"
#include "aesim/receiver/stream_consumer.hpp"
#include "aesim/receiver/stream_rules.hpp"

namespace aesim {

// A receiver's whole clock domain as one process: the gated clock, the receiver
// (ReceiverCycleModel), the consumer of its event stream and the stream's rules, stepped together
// once per rising edge; or, in the model's place, a SteppedReceiver (the Verilated RTL as a plain
// C++ model, with its scoreboard). A tile with such a receiver needs nothing else on its clock: its
// outputs toward the bus (Ack, and the overflow count the bus reads when Ack rises) are the only
// wires it drives. A Verilated receiver has a clock wire and ports, and its tile keeps GatedClock,
// EventSink and StreamMonitor as separate processes on those wires (receiver/receiver_module).
//
// The same edges as GatedClock (rising at k * period, stopped while the receiver is idle with Req
// low, the next edge after Req rises), the same values latched at each edge, so the same results
// (a test runs both and compares every record): with at most one process activation per edge
// (several edges an activation with set_wires_hold_until) instead of a clock thread's two
// wake-ups, a clock wire toggling twice and four processes on its edge.
class ReferenceClockDomain : public sc_core::sc_module {
 public:
  struct Clock {
    sc_core::sc_time period;
    unsigned prescale = 1;
    int ts_width = 32;
    sc_core::sc_time free_running_until = sc_core::SC_ZERO_TIME;
  };
  ReferenceClockDomain(const sc_core::sc_module_name& name, ReceiverSignals& s, const Clock& clock,
                       const ReceiverCycleModel::Config& config, StreamConsumer consumer);
  SC_HAS_PROCESS(ReferenceClockDomain);

  std::uint64_t edges() const { return edges_; }
  // Tells the domain until when (ps) the bus wires cannot change but in answer to Ack: the tile's
  // next firing. The bus (ClockedAlohaBus) answers Ack rising by releasing every wire (each pixel
  // driving lets go; one firing while Ack is high withdraws) and Ack falling by changing none.
  // Then the edges before the firing are stepped in one activation, the kernel woken only where
  // Ack or the overflow count changes (the bus must see those at their edge) and after the
  // firing. Without it, one activation per edge.
  void set_wires_hold_until(std::function<std::uint64_t()> until) { wires_hold_until_ = std::move(until); }
  std::uint64_t violations() const;
  // Steps `receiver` (the Verilated RTL, say) at each edge in place of the reference model. Called
  // before the simulation starts.
  void step(std::unique_ptr<SteppedReceiver> receiver) {
    stepped_ = std::move(receiver);
    outputs_ = &stepped_->outputs();
  }
  const SteppedReceiver* stepped() const { return stepped_.get(); }
  // Whether the receiver holds nothing (no handshake, an empty FIFO) after the last edge stepped.
  bool idle() const { return out().idle; }

 private:
  void on_wake();
  // Edge k_: the stream's rules, the consumer and the receiver latch what was held before it.
  void step_edge();
  // After edge k_: whether the clock stops there (then waiting for Req to rise).
  bool stops_after_edge();
  // The stream and status outputs held now (after the last edge).
  StreamView view() const;
  const ReceiverCycleModel::Outputs& out() const { return *outputs_; }
  // Req as the next edge sees it: low once Ack has risen, though the bus lets go only in the
  // delta cycle after this activation.
  bool req() const { return !released_ && s_.req.read(); }
  // The timestamp counter at edge k_: k_ / prescale, within ts_width bits.
  std::uint64_t stamp_at_edge();

  ReceiverSignals& s_;
  Clock clock_;
  std::uint64_t period_ps_, ts_mask_;
  std::uint32_t fifo_limit_;
  bool ts_external_;
  ReceiverCycleModel model_;
  std::unique_ptr<SteppedReceiver> stepped_;  // stepped instead of model_, when set
  const ReceiverCycleModel::Outputs* outputs_;  // the outputs of whichever is stepped
  bool ready_ = true;  // the consumer's ready, held since the last edge
  StreamConsumer consumer_;
  StreamRules rules_;
  std::function<std::uint64_t()> wires_hold_until_;
  bool running_ = false;
  bool released_ = false;  // Ack rose at the edge this activation wrote: the bus releases the wires
  bool stepped_ahead_ = false;  // edge k_ is stepped; its outputs are driven when the kernel reaches it
  std::uint64_t k_ = 0;  // the rising edge the clock waits for: at k_ * period
  // k_ / prescale and its remainder at edge stamp_edge_, counted on from edge to edge.
  std::uint64_t stamp_edge_ = 0, stamp_quotient_ = 0, stamp_remainder_ = 0;
  std::uint64_t edges_ = 0;
};

}  // namespace aesim
