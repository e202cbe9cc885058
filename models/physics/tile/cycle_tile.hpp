#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <systemc>

#include "aesim/array/address_map.hpp"
#include "aesim/bus/clocked_aloha_bus.hpp"
#include "aesim/bus/bus_waveform.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/receiver/event_sink.hpp"
#include "aesim/receiver/gated_clock.hpp"
#include "aesim/receiver/receiver_module.hpp"
#include "aesim/receiver/reference_clock_domain.hpp"
#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/receiver/stream_monitor.hpp"
#include "aesim/waveform/vcd_recorder.hpp"

namespace aesim {

// One tile at the cycle fidelity, as it would be on the chip: its wires, the pixel side of the
// ALOHA bus driving them (which checks the handshake), the receiver with its gated clock, the
// consumer of the receiver's event stream and the stream's rules, and with a VCD the recorder of
// the wires. Firings enter through bus().
//
// The reference receiver (no factory in the options) runs as one process per clock edge
// (ReferenceClockDomain); a receiver from a factory (the Verilated RTL, a variant under test, or
// the reference model as a module) gets a clock wire and its own processes beside the sink and
// the stream monitor. Both give the same records. A tile named in outside_receivers has the clock
// wire, sink and monitor and leaves the receiver to whoever binds to wires().
class CycleTile : public sc_core::sc_module {
 public:
  CycleTile(const sc_core::sc_module_name& name, std::uint32_t tile, const AddressMap& map,
            const SensorConfig& config, EventLog& log, VcdRecorder* vcd, const CycleOptions& options);

  EventBus& bus() { return bus_; }
  // The tile's wires, for a receiver outside it (CycleOptions::outside_receivers).
  ReceiverSignals& wires() { return s_; }
  bool receiver_outside() const { return outside_; }
  // What an outside receiver drives, told before the simulation starts. Without idle, the clock
  // runs free until `duration` and then stops once Req and Ack are low; without the event and FIFO
  // counters, the stream's rule that nothing vanishes is not checked.
  void outside_receiver_reports(bool idle, bool counters, sc_core::sc_time duration);
  // Whether nothing more can happen on the tile until a pixel fires: Req and Ack low and the
  // receiver idle (an outside receiver that reports no idle: Req and Ack low).
  bool quiescent() const;
  // Gives the reference receiver's clock domain the time (ps) of this tile's next firing, from
  // whatever drives the bus, so that it steps the edges before it in one activation.
  void set_next_firing(std::function<std::uint64_t()> next_firing_ps);
  // Adds the tile's bus wires (req, addr, contention, ack) to a caller's trace file, each named
  // `prefix` + its name; with a clock wire (a factory's or an outside receiver) also the clock,
  // reset, idle and the output stream. The reference receiver's domain has no clock wire: its
  // stream lives inside the process that steps it.
  void trace_wires(sc_core::sc_trace_file* file, const std::string& prefix) const;

  // What the tile saw: handshake and stream rule breaks, receiver clock edges simulated, the
  // co-simulation scoreboard's compared beats and mismatches (RTL receivers only), and the mean
  // transaction time measured on the wires.
  struct Stats {
    std::uint64_t protocol_violations = 0, clock_edges = 0, scoreboard_beats = 0, scoreboard_mismatches = 0;
    double measured_tau = 0;
  };
  Stats stats() const;

 private:
  ReceiverSignals s_;
  bool outside_ = false;
  bool idle_reported_ = true;  // whether s_.idle is driven (not by an outside receiver without it)
  std::unique_ptr<ReferenceClockDomain> domain_;  // the reference receiver's clock domain, or
  std::unique_ptr<GatedClock> clock_;             // a factory's receiver with its clock wire,
  std::unique_ptr<ReceiverModule> receiver_;
  std::unique_ptr<EventSink> sink_;               // sink and stream monitor
  std::unique_ptr<StreamMonitor> stream_monitor_;
  std::unique_ptr<BusWaveform> waveform_;  // with a VCD only
  ClockedAlohaBus bus_;
};

// The receiver clock's period: a whole number of picoseconds, so edges fall exactly on SystemC's
// time grid (at its default resolution, 1 ps; check_time_resolution() says whether another holds it).
long long receiver_clock_period_ps(const ReceiverParams& receiver);
sc_core::sc_time receiver_clock_period(const ReceiverParams& receiver);
// Throws InputError when SystemC's time resolution (a caller's sc_main may have set its own before
// the model was made) cannot hold the receiver clock's period as a whole number of its steps, two
// at least: the clock would run at another rate, or not at all.
void check_time_resolution(const ReceiverParams& receiver);

}  // namespace aesim
