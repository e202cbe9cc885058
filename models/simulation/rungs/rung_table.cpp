#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/rungs/rung.hpp"

namespace aesim {

// Each defined in its own file.
const Rung& queue_rung();
const Rung& event_rung();
const Rung& pixel_processes_rung();
const Rung& cycle_rung();
const Rung& fixed_step_rung();

const std::vector<const Rung*>& rung_table() {
  static const std::vector<const Rung*> table = {&queue_rung(), &event_rung(), &pixel_processes_rung(),
                                                 &cycle_rung(), &fixed_step_rung()};
  return table;
}

const Rung& rung_for(Fidelity fidelity) {
  for (const Rung* rung : rung_table()) {
    if (rung->fidelity() == fidelity) return *rung;
  }
  throw InputError(fmt::format("sim.fidelity={}: this build has no such rung", to_string(fidelity)));
}

namespace {

// The rungs that have a capability, for messages: "cycle", "cycle or event".
std::string rungs_with(bool RungCapabilities::*capability) {
  std::string names;
  for (const Rung* rung : rung_table()) {
    if (!(rung->capabilities().*capability)) continue;
    names += (names.empty() ? "" : " or ") + std::string(to_string(rung->fidelity()));
  }
  return names;
}

}  // namespace

const Rung& choose_rung(const SensorConfig& config, const SimulationRequest& request) {
  const bool rtl = config.receiver.model == ReceiverModel::Rtl;
  const Rung* chosen = nullptr;
  if (config.sim.fidelity == Fidelity::Auto) {
    for (const Rung* rung : rung_table()) {
      const RungCapabilities can = rung->capabilities();
      if (can.exact && (can.waveforms || !request.waveforms) && (can.receiver_model || !rtl)) {
        chosen = rung;
        break;
      }
    }
    if (!chosen) throw std::logic_error("no rung serves the request");
  } else {
    chosen = &rung_for(config.sim.fidelity);
  }
  const RungCapabilities can = chosen->capabilities();
  const char* name = to_string(chosen->fidelity());
  if (request.waveforms && !can.waveforms) {
    throw InputError(fmt::format("--vcd dumps the clocked bus wires, which exist at sim.fidelity={} (or auto), not {}",
                                 rungs_with(&RungCapabilities::waveforms), name));
  }
  if (rtl && !can.receiver_model) {
    throw InputError(fmt::format("receiver.model=rtl runs at sim.fidelity={} (or auto), not {}",
                                 rungs_with(&RungCapabilities::receiver_model), name));
  }
  if (config.pixel.shot_noise && !can.shot_noise) {
    throw InputError(fmt::format("pixel.shot_noise is not modelled at sim.fidelity={}", name));
  }
  chosen->check(config);
  return *chosen;
}

}  // namespace aesim
