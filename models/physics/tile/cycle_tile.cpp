#include "aesim/tile/cycle_tile.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

long long receiver_clock_period_ps(const ReceiverParams& receiver) {
  return std::max<long long>(1, std::llround(1e12 / receiver.clock));
}

sc_core::sc_time receiver_clock_period(const ReceiverParams& receiver) {
  return sc_core::sc_time(static_cast<double>(receiver_clock_period_ps(receiver)), sc_core::SC_PS);
}

void check_time_resolution(const ReceiverParams& receiver) {
  const double resolution_ps = sc_core::sc_get_time_resolution().to_seconds() * 1e12;
  const long long period_ps = receiver_clock_period_ps(receiver);
  const double steps = static_cast<double>(period_ps) / resolution_ps, whole = std::round(steps);
  if (whole >= 2 && std::abs(steps - whole) < 1e-9 * whole) return;  // the resolution in seconds is a double
  throw InputError(fmt::format("SystemC's time resolution, {}, cannot hold the receiver clock's period ({} ps at "
                               "receiver.clock {:g} Hz) as a whole number of its steps: set a finer one before the "
                               "model is made (sc_core::sc_set_time_resolution(1, sc_core::SC_PS), SystemC's default)",
                               sc_core::sc_get_time_resolution().to_string(), period_ps, receiver.clock));
}

CycleTile::CycleTile(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
                     const SensorConfig& config, EventLog& log, VcdRecorder* vcd, const CycleOptions& options)
    : sc_module(name),
      waveform_(vcd ? std::make_unique<BusWaveform>("waveform", fmt::format("tile{}", tile), map.bus_bits(), *vcd)
                    : nullptr),
      bus_("bus", s_, receiver_clock_period(config.receiver), config.bus.contention_detect, log) {
  const ReceiverCycleModel::Config rc = receiver_model_config(config.receiver, config.bus.contention_detect, options);
  const sc_core::sc_time period = receiver_clock_period(config.receiver);
  const sc_core::sc_time free_running_until =
      options.free_running_clock ? sc_core::sc_time(config.sim.duration, sc_core::SC_SEC) : sc_core::SC_ZERO_TIME;
  StreamConsumer consumer(tile, map, receiver_tick(config.receiver), kReceiverTsWidth, log);
  if (options.sink_ready) consumer.set_ready_pattern(options.sink_ready);
  outside_ = std::find(options.outside_receivers.begin(), options.outside_receivers.end(), tile) !=
             options.outside_receivers.end();
  if (!options.receiver && !outside_) {
    domain_ = std::make_unique<ReferenceClockDomain>(
        "receiver", s_, ReferenceClockDomain::Clock{period, rc.prescale, kReceiverTsWidth, free_running_until}, rc,
        std::move(consumer));
    if (options.stepped_receiver) domain_->step(options.stepped_receiver(tile, rc));
  } else {
    clock_ = std::make_unique<GatedClock>("clock", s_, period, rc.prescale, kReceiverTsWidth, free_running_until);
    if (!outside_) receiver_ = options.receiver("receiver", tile, s_, rc);
    sink_ = std::make_unique<EventSink>("sink", s_, std::move(consumer));
    stream_monitor_ = std::make_unique<StreamMonitor>("stream_monitor", s_);
  }
  s_.prescale.write(rc.prescale);
  s_.fifo_limit.write(rc.fifo_limit);
  s_.discard_collisions.write(rc.discard_collisions);
  s_.ts_external.write(rc.ts_external);
  if (waveform_) {
    waveform_->req(s_.req);
    waveform_->ack(s_.ack);
    waveform_->contention(s_.contention);
    waveform_->addr(s_.addr);
  }
}

void CycleTile::outside_receiver_reports(bool idle, bool counters, sc_core::sc_time duration) {
  idle_reported_ = idle;
  if (!idle) clock_->run_free_then_stop_when_quiet(duration);
  if (!counters) stream_monitor_->without_counters();
}

bool CycleTile::quiescent() const {
  if (s_.req.read() || s_.ack.read()) return false;
  if (domain_) return domain_->idle();
  return !idle_reported_ || s_.idle.read();
}

void CycleTile::set_next_firing(std::function<std::uint64_t()> next_firing_ps) {
  if (!domain_) return;
  domain_->set_wires_hold_until([this, next = std::move(next_firing_ps)] {
    // A firing that fell on this edge joins 1 ps after it.
    return bus_.joins_pending() ? sc_core::sc_time_stamp().value() + 1 : next();
  });
}

CycleTile::Stats CycleTile::stats() const {
  Stats s;
  s.protocol_violations = bus_.handshake_violations() + (domain_ ? domain_->violations() : stream_monitor_->violations());
  s.clock_edges = domain_ ? domain_->edges() : clock_->edges();
  if (receiver_) {
    s.scoreboard_beats = receiver_->scoreboard_beats();
    s.scoreboard_mismatches = receiver_->scoreboard_mismatches();
  } else if (domain_ && domain_->stepped()) {
    s.scoreboard_beats = domain_->stepped()->scoreboard_beats();
    s.scoreboard_mismatches = domain_->stepped()->scoreboard_mismatches();
  }
  s.measured_tau = bus_.measured_tau();
  return s;
}

void CycleTile::trace_wires(sc_core::sc_trace_file* file, const std::string& prefix) const {
  sc_core::sc_trace(file, s_.req, prefix + "req");
  sc_core::sc_trace(file, s_.addr, prefix + "addr");
  sc_core::sc_trace(file, s_.contention, prefix + "contention");
  sc_core::sc_trace(file, s_.ack, prefix + "ack");
  if (domain_) return;
  sc_core::sc_trace(file, s_.clk, prefix + "clk");
  sc_core::sc_trace(file, s_.rst_n, prefix + "rst_n");
  sc_core::sc_trace(file, s_.idle, prefix + "idle");
  sc_core::sc_trace(file, s_.evt_valid, prefix + "evt_valid");
  sc_core::sc_trace(file, s_.evt_ready, prefix + "evt_ready");
  sc_core::sc_trace(file, s_.evt_addr, prefix + "evt_addr");
  sc_core::sc_trace(file, s_.evt_ts, prefix + "evt_ts");
  sc_core::sc_trace(file, s_.evt_flags, prefix + "evt_flags");
}

}  // namespace aesim
