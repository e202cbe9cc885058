#include "aesim/cosim/stepped_rtl_receiver.hpp"

#include <verilated.h>

#include "Vaer_receiver_drop_stepped.h"
#include "Vaer_receiver_hold_stepped.h"
#include "aesim/cosim/output_compare.hpp"

namespace aesim {
namespace {

template <class V>
class SteppedRtlReceiver : public SteppedReceiver {
 public:
  explicit SteppedRtlReceiver(const ReceiverCycleModel::Config& config)
      : rtl_("rtl"), reference_(config) {
    rtl_.prescale_i = config.prescale;
    rtl_.fifo_limit_i = config.fifo_limit;
    rtl_.discard_collisions_i = config.discard_collisions;
    rtl_.ts_external_i = config.ts_external;
    rtl_.evt_ready_i = 1;
    // Reset held low, then released: as the tile's reset wire at t = 0.
    rtl_.clk_i = 0;
    rtl_.rst_ni = 0;
    rtl_.eval();
    rtl_.rst_ni = 1;
    rtl_.eval();
    reference_.reset();
    read_outputs();
  }
  ~SteppedRtlReceiver() override { rtl_.final(); }

  void clock(const ReceiverCycleModel::Inputs& in, std::uint64_t ts) override {
    // A beat the consumer takes at this edge: offered and ready before it.
    if (out_.valid && in.ready) ++beats_;
    rtl_.req_i = in.req;
    rtl_.addr_i = in.addr;
    rtl_.contention_i = in.contention;
    rtl_.evt_ready_i = in.ready;
    rtl_.ts_i = static_cast<std::uint32_t>(ts);
    rtl_.clk_i = 1;
    rtl_.eval();
    rtl_.clk_i = 0;
    rtl_.eval();
    ReceiverCycleModel::Inputs model_in = in;
    model_in.ts = ts;
    reference_.clock(model_in);
    read_outputs();
    compare();
  }
  const ReceiverCycleModel::Outputs& outputs() const override { return out_; }
  std::uint64_t scoreboard_mismatches() const override { return mismatches_; }
  std::uint64_t scoreboard_beats() const override { return beats_; }

 private:
  void read_outputs() {
    out_.ack = rtl_.ack_o;
    out_.valid = rtl_.evt_valid_o;
    out_.beat.ts = rtl_.evt_ts_o;
    out_.beat.addr = rtl_.evt_addr_o;
    out_.beat.flags = rtl_.evt_flags_o;
    out_.events = rtl_.events_o;
    out_.collisions = rtl_.collisions_o;
    out_.overflows = rtl_.overflows_o;
    out_.fifo_count = rtl_.fifo_count_o;
    out_.idle = rtl_.idle_o;
  }
  void compare() {
    compare_outputs(out_, reference_.outputs(), [this](const char*, std::uint64_t r, std::uint64_t m) {
      if (r != m) ++mismatches_;
    });
  }

  // In Verilator's default context, as the SystemC models are: a thread that has constructed a
  // model in one context cannot construct another in a different one (Verilator aborts).
  V rtl_;
  ReceiverCycleModel reference_;
  ReceiverCycleModel::Outputs out_;
  std::uint64_t mismatches_ = 0, beats_ = 0;
};

}  // namespace

std::unique_ptr<SteppedReceiver> make_stepped_rtl_receiver(FullPolicy policy, const ReceiverCycleModel::Config& config) {
  if (policy == FullPolicy::Hold) return std::make_unique<SteppedRtlReceiver<Vaer_receiver_hold_stepped>>(config);
  return std::make_unique<SteppedRtlReceiver<Vaer_receiver_drop_stepped>>(config);
}

}  // namespace aesim
