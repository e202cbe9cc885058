#include "top/imager_simulation.hpp"

#include <chrono>
#include <memory>
#include <systemc>

#include <fmt/format.h>

#include "array/imager.hpp"
#include "config/input_error.hpp"

namespace aesim {

Fidelity resolve_fidelity(const SensorConfig& config) {
  switch (config.sim.fidelity) {
    case Fidelity::Auto:
    case Fidelity::Event:
      return Fidelity::Event;
    case Fidelity::Queue:
    case Fidelity::Cycle:
      break;
  }
  throw InputError(fmt::format("sim.fidelity={} is not modelled yet; use event or auto",
                               to_string(config.sim.fidelity)));
}

SimulationResult simulate(const SensorConfig& config, const Photocurrents& light) {
  const Fidelity fidelity = resolve_fidelity(config);
  const auto wall_start = std::chrono::steady_clock::now();

  // A fresh kernel per run: SystemC allows one elaboration per simulation context. The old
  // context is deliberately not deleted: SystemC 2.3.4 still touches it from static teardown
  // (valgrind shows invalid reads), and once the run's modules are gone it holds only a few KB.
  sc_core::sc_curr_simcontext = new sc_core::sc_simcontext;
  sc_core::sc_default_global_context = sc_core::sc_curr_simcontext;
  sc_core::sc_report_handler::set_actions(sc_core::SC_ID_NO_SC_START_ACTIVITY_, sc_core::SC_DO_NOTHING);

  const AddressMap map(config.array);
  SimulationResult result{EventLog(map.tiles()), {}};
  {
    Imager imager("imager", config, light, result.log);
    // Every pixel stops scheduling itself past sim.duration, so the kernel starves exactly
    // when the run is complete, with firings at t == duration included.
    sc_core::sc_start();
  }
  result.log.finish();
  result.facts.fidelity = fidelity;
  result.facts.tau_s = config.bus.t_event;
  result.facts.sim_time_s = config.sim.duration;
  result.facts.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace aesim
