#include "tile/cycle_tile.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace aesim {

sc_core::sc_time receiver_clock_period(const ReceiverParams& receiver) {
  return sc_core::sc_time(static_cast<double>(std::max<long long>(1, std::llround(1e12 / receiver.clock))),
                          sc_core::SC_PS);
}

CycleTile::CycleTile(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
                     const SensorConfig& config, EventLog& log, VcdRecorder* vcd, const CycleOptions& options)
    : sc_module(name),
      clock_("clock", s_, receiver_clock_period(config.receiver), receiver_prescale(config.receiver), kReceiverTsWidth,
             options.free_running_clock ? sc_core::sc_time(config.sim.duration, sc_core::SC_SEC)
                                        : sc_core::SC_ZERO_TIME),
      receiver_((options.receiver ? options.receiver : reference_receiver_factory())(
          "receiver", tile, s_, receiver_model_config(config.receiver, config.bus.contention_detect, options))),
      sink_("sink", s_, tile, map, receiver_tick(config.receiver), kReceiverTsWidth, log),
      monitor_("monitor", fmt::format("tile{}", tile), map.bus_bits(), vcd),
      stream_monitor_("stream_monitor", s_),
      bus_("bus", s_, receiver_clock_period(config.receiver), config.bus.contention_detect, log) {
  if (options.sink_ready) sink_.set_ready_pattern(options.sink_ready);
  const ReceiverCycleModel::Config rc = receiver_model_config(config.receiver, config.bus.contention_detect, options);
  s_.prescale.write(rc.prescale);
  s_.fifo_limit.write(rc.fifo_limit);
  s_.discard_collisions.write(rc.discard_collisions);
  s_.ts_external.write(rc.ts_external);
  monitor_.req(s_.req);
  monitor_.ack(s_.ack);
  monitor_.contention(s_.contention);
  monitor_.addr(s_.addr);
}

CycleTile::Stats CycleTile::stats() const {
  Stats s;
  s.protocol_violations = monitor_.violations() + stream_monitor_.violations();
  s.clock_edges = clock_.edges();
  s.scoreboard_beats = receiver_->scoreboard_beats();
  s.scoreboard_mismatches = receiver_->scoreboard_mismatches();
  s.measured_tau = bus_.measured_tau();
  return s;
}

}  // namespace aesim
