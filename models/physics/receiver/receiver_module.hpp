#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <systemc>

#include "aesim/config/sensor_config.hpp"
#include "aesim/receiver/receiver_cycle_model.hpp"
#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/receiver/stepped_receiver.hpp"

namespace aesim {

// A tile's receiver at the cycle fidelity: the reference model, or the Verilated RTL with a
// scoreboard stepping the reference beside it.
class ReceiverModule : public sc_core::sc_module {
 public:
  using sc_core::sc_module::sc_module;
  virtual std::uint64_t scoreboard_mismatches() const { return 0; }
  virtual std::uint64_t scoreboard_beats() const { return 0; }
};

// Makes tile `tile`'s receiver, bound to its signals.
using ReceiverFactory = std::function<std::unique_ptr<ReceiverModule>(
    const std::string& name, std::uint32_t tile, ReceiverSignals& signals, const ReceiverCycleModel::Config& config)>;

// The reference receiver (models/physics/receiver/reference_receiver) as a factory.
ReceiverFactory reference_receiver_factory();

// How the cycle fidelity builds and runs each tile's receiver.
struct CycleOptions {
  // Empty: the reference model (or the RTL, when the run's receiver.model says so).
  ReceiverFactory receiver;
  // With no `receiver`: a receiver the tile's clock domain steps in place of the reference model
  // (the RTL as a plain C++ model), made for each tile.
  std::function<std::unique_ptr<SteppedReceiver>(std::uint32_t tile, const ReceiverCycleModel::Config&)> stepped_receiver;
  // Tiles whose receiver lives outside the tile (the caller's, wired to the tile's signals after
  // the tile is built): such a tile has its clock, consumer and stream monitor but no receiver.
  std::vector<std::uint32_t> outside_receivers;
  // Keep the receiver clock running for the whole run and let the receiver count its own
  // timestamps, instead of stopping the clock while the bus is idle and feeding it the
  // free-running count. Both give the same results (a test shows it); this one costs more.
  bool free_running_clock = false;
  // Whether the consumer of the event stream is ready in a given clock cycle (always if empty).
  std::function<bool(std::uint64_t)> sink_ready;
};

// The receiver's settings from the sensor: clock cycles per timestamp tick (receiver.tick rounded
// to a whole number of clock periods, at least one) and the tick that results.
unsigned receiver_prescale(const ReceiverParams& receiver);
double receiver_tick(const ReceiverParams& receiver);
// The receiver as built, set up for the run: `discard_collisions` is bus.contention_detect.
ReceiverCycleModel::Config receiver_model_config(const ReceiverParams& receiver, bool discard_collisions,
                                                 const CycleOptions& options);

// Limits of the receiver as built (rtl/aer_receiver.v parameters in aesim's build).
inline constexpr int kReceiverAddrWidth = 16;
inline constexpr int kReceiverTsWidth = 32;
inline constexpr unsigned kReceiverFifoCapacity = 64;
inline constexpr unsigned kReceiverMaxPrescale = (1u << 24) - 1;

}  // namespace aesim
