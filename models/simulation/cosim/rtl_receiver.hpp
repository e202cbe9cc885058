#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <fmt/format.h>
// Verilator's SystemC runtime expects SystemC's names in the global namespace.
#include <systemc.h>
#include <verilated.h>
#include <verilated_vcd_c.h>

#include "aesim/cosim/dot_free_vcd_file.hpp"
#include "aesim/cosim/output_compare.hpp"
#include "aesim/receiver/receiver_cycle_model.hpp"
#include "aesim/receiver/receiver_module.hpp"
#include "aesim/receiver/receiver_signals.hpp"

namespace aesim {

// A Verilated rtl/aer_receiver.v (class V) bound to a tile's receiver signals, with a co-simulation
// scoreboard: the reference ReceiverCycleModel is clocked beside the RTL with the very inputs the
// RTL sees at each rising edge, and at each falling edge every output of the RTL (Ack, the stream's
// valid and beat, every counter, FIFO fill, idle) is compared with the model's.
// Verilator tracing of the RTL's internal signals into `path` for the time window [from, to].
struct RtlTrace {
  std::string path;
  sc_core::sc_time from, to;
};

template <class V>
class RtlReceiver : public ReceiverModule {
 public:
  RtlReceiver(const sc_core::sc_module_name& name, ReceiverSignals& s, const ReceiverCycleModel::Config& config)
      : ReceiverModule(name), rtl_("rtl"), reference_(config), s_(s) {
    rtl_.clk_i(s.clk);
    rtl_.rst_ni(s.rst_n);
    rtl_.req_i(s.req);
    rtl_.addr_i(s.addr);
    rtl_.contention_i(s.contention);
    rtl_.ack_o(s.ack);
    rtl_.prescale_i(s.prescale);
    rtl_.fifo_limit_i(s.fifo_limit);
    rtl_.discard_collisions_i(s.discard_collisions);
    rtl_.ts_external_i(s.ts_external);
    rtl_.ts_i(s.ts);
    rtl_.evt_valid_o(s.evt_valid);
    rtl_.evt_ready_i(s.evt_ready);
    rtl_.evt_ts_o(s.evt_ts);
    rtl_.evt_addr_o(s.evt_addr);
    rtl_.evt_flags_o(s.evt_flags);
    rtl_.events_o(s.events);
    rtl_.collisions_o(s.collisions);
    rtl_.overflows_o(s.overflows);
    rtl_.fifo_count_o(s.fifo_count);
    rtl_.idle_o(s.idle);
    SC_METHOD(on_rise);
    sensitive << s.clk.posedge_event();
    dont_initialize();
    SC_METHOD(on_fall);
    sensitive << s.clk.negedge_event();
    dont_initialize();
    SC_METHOD(on_reset);
    sensitive << s.rst_n;
  }
  SC_HAS_PROCESS(RtlReceiver);

  // Dumps every internal signal at each clock edge within the window (call before the run).
  void trace_internals(const RtlTrace& t) {
    Verilated::traceEverOn(true);
    trace_ = t;
    tracing_ = true;
    SC_METHOD(after_edge);
    sensitive << s_.clk;
    dont_initialize();
    SC_METHOD(dump_window);
    sensitive << settled_;
    dont_initialize();
  }

  // The RTL's final blocks run when the design is torn down, as Verilator's examples do at the end
  // of simulation; then the trace is closed.
  ~RtlReceiver() override {
    rtl_.final();
    if (vcd_) vcd_->close();
  }

  std::uint64_t scoreboard_mismatches() const override { return mismatches_; }
  std::uint64_t scoreboard_beats() const override { return beats_; }
  const std::string& first_mismatch() const { return first_mismatch_; }

 private:
  void on_rise() {
    if (!s_.rst_n.read()) return;
    if (s_.evt_valid.read() && s_.evt_ready.read()) ++beats_;
    reference_.clock(sample_inputs(s_));
  }
  void on_reset() {
    if (!s_.rst_n.read()) reference_.reset();
  }
  void on_fall() {
    ReceiverCycleModel::Outputs rtl;
    rtl.ack = s_.ack.read();
    rtl.valid = s_.evt_valid.read();
    rtl.beat = {s_.evt_ts.read(), s_.evt_addr.read(), s_.evt_flags.read()};
    rtl.events = s_.events.read();
    rtl.collisions = s_.collisions.read();
    rtl.overflows = s_.overflows.read();
    rtl.fifo_count = s_.fifo_count.read();
    rtl.idle = s_.idle.read();
    compare_outputs(rtl, reference_.outputs(),
                    [this](const char* what, std::uint64_t r, std::uint64_t m) { check(what, r, m); });
  }
  void start_of_simulation() override {
    if (!tracing_) return;
    vcd_file_ = std::make_unique<DotFreeScopesFile>();
    vcd_ = std::make_unique<VerilatedVcdC>(vcd_file_.get());
    rtl_.trace(vcd_.get(), 99);
    vcd_->open(trace_.path.c_str());
  }
  // The RTL evaluates in the delta where the clock changes; dump one delta later.
  void after_edge() { settled_.notify(sc_core::SC_ZERO_TIME); }
  void dump_window() {
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    if (now >= trace_.from && now <= trace_.to) vcd_->dump(static_cast<std::uint64_t>(now.value()));
  }
  void check(const char* what, std::uint64_t rtl, std::uint64_t model) {
    if (rtl == model) return;
    if (mismatches_++ == 0) {
      first_mismatch_ = fmt::format("{} at {}: rtl {} reference {}", what, sc_core::sc_time_stamp().to_string(), rtl, model);
    }
  }

  V rtl_;
  ReceiverCycleModel reference_;
  ReceiverSignals& s_;
  std::uint64_t mismatches_ = 0, beats_ = 0;
  std::string first_mismatch_;
  bool tracing_ = false;
  RtlTrace trace_;
  sc_core::sc_event settled_;
  std::unique_ptr<DotFreeScopesFile> vcd_file_;  // outlives vcd_, which writes through it
  std::unique_ptr<VerilatedVcdC> vcd_;
};

// The RTL receiver in the build's full-FIFO policy, as a factory for the imager. With
// trace_path, tile N's receiver is traced to trace_path(N) within [from, to].
ReceiverFactory rtl_receiver_factory(FullPolicy policy, std::function<std::string(int)> trace_path = {},
                                     sc_core::sc_time from = sc_core::SC_ZERO_TIME,
                                     sc_core::sc_time to = sc_core::SC_ZERO_TIME);

}  // namespace aesim
