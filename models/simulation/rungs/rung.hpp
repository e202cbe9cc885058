#pragma once
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/events/run_facts.hpp"
#include "aesim/rungs/simulation_request.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/waveform/vcd_recorder.hpp"

namespace aesim {

// What a rung can produce, for `auto` and for refusing a request a rung cannot serve.
struct RungCapabilities {
  bool exact = false;           // firing times from the pixel physics in closed form: auto may pick it
  bool waveforms = false;       // bus wires to dump (--vcd)
  bool receiver_model = false;  // a clocked receiver: the reference model or the RTL (receiver.model)
  bool shot_noise = true;       // models pixel.shot_noise
  bool stepped = false;         // integrates on a clock of period sim.step
};

// Everything one run of a rung works on; the rung writes into `log`.
struct RungRun {
  const ResolvedConfig& config;
  const Photocurrents& photocurrents;
  const AddressMap& map;
  const SimulationRequest& request;
  EventLog& log;
  VcdRecorder* vcd;  // when request.waveforms
};

// One fidelity rung: a way of simulating the array, from the paper's event queue to the clocked
// bus with the receiver RTL in the loop. A rung is one file (rungs/NAME_rung.cpp) and one line of
// the table in rung_table.cpp.
class Rung {
 public:
  virtual ~Rung() = default;
  virtual Fidelity fidelity() const = 0;
  virtual RungCapabilities capabilities() const = 0;
  // Refuses, naming the key, a configuration this rung cannot model (InputError); before any work.
  virtual void check(const SensorConfig& config) const { (void)config; }
  // The receiver's timestamp resolution in this rung's output.
  virtual double tick(const SensorConfig& config) const { return config.receiver.tick; }
  // Simulates sim.duration into run.log (settled, not yet finished) and fills the facts the rung
  // knows (tau and its own counters); simulate() fills the rest.
  virtual void run(const RungRun& run, RunFacts& facts) const = 0;
};

// Every rung, in the ladder's order: the paper's event queue, the exact event-driven reference,
// then the SystemC rungs (a process per pixel, the clocked bus, the fixed step). `auto` takes the
// first exact one that can serve the request.
const std::vector<const Rung*>& rung_table();
const Rung& rung_for(Fidelity fidelity);

// The rung a run uses: sim.fidelity, with auto resolved to the cheapest exact rung that can
// produce what was asked, checked against the request and the configuration (InputError naming
// the key when it cannot serve them).
const Rung& choose_rung(const SensorConfig& config, const SimulationRequest& request);

}  // namespace aesim
