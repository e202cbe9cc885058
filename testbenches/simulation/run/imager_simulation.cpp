#include "run/imager_simulation.hpp"

#include <chrono>
#include <memory>
#include <systemc>

#include <fmt/format.h>

#include "rungs/imager.hpp"
#include "rungs/run_budget.hpp"
#include "cosim/rtl_receiver.hpp"
#include "kernel/systemc_kernel.hpp"
#include "errors/input_error.hpp"

namespace aesim {

Fidelity resolve_fidelity(const SensorConfig& config, const SimulationRequest& request) {
  switch (config.sim.fidelity) {
    case Fidelity::Auto:
      // Waveforms and a receiver model exist only at the cycle fidelity.
      return request.waveforms || config.receiver.model == ReceiverModel::Rtl ? Fidelity::Cycle : Fidelity::Event;
    case Fidelity::Event:
      if (request.waveforms) {
        throw InputError("--vcd dumps the clocked bus wires, which exist at sim.fidelity=cycle (or auto), not event");
      }
      if (config.receiver.model == ReceiverModel::Rtl) {
        throw InputError("receiver.model=rtl runs at sim.fidelity=cycle (or auto), not event");
      }
      return Fidelity::Event;
    case Fidelity::Cycle:
      return Fidelity::Cycle;
    case Fidelity::PixelProcesses:
    case Fidelity::FixedStep:
    case Fidelity::Queue:
      break;
  }
  if (request.waveforms || config.receiver.model == ReceiverModel::Rtl) {
    throw InputError(fmt::format("sim.fidelity={} has event-level buses: no wires for --vcd, no receiver model",
                                 to_string(config.sim.fidelity)));
  }
  if (config.sim.fidelity == Fidelity::FixedStep && config.pixel.shot_noise) {
    throw InputError("pixel.shot_noise is not modelled at sim.fidelity=fixed_step");
  }
  return config.sim.fidelity;
}

SimulationResult simulate(const SensorConfig& config, const Photocurrents& light, const SimulationRequest& request) {
  const Fidelity fidelity = resolve_fidelity(config, request);
  check_work(config, light, fidelity);
  const auto wall_start = std::chrono::steady_clock::now();

  const AddressMap map(config.array);
  SimulationResult result{EventLog(map.tiles(), request.keep_truth), {}, nullptr};
  result.log.count_pixels(static_cast<std::size_t>(map.rows()) * static_cast<std::size_t>(map.cols()),
                          static_cast<std::uint32_t>(map.cols()), config.analysis.window);
  if (request.waveforms) result.vcd = std::make_unique<VcdRecorder>(request.vcd_from, request.vcd_to);
  {
    const ScopedKernel kernel;  // first in the block, so the imager is gone before its context
    CycleOptions cycle;
    if (config.receiver.model == ReceiverModel::Rtl) {
      cycle.receiver = rtl_receiver_factory(config.receiver.full_policy, request.rtl_trace_path,
                                            sc_core::sc_time(request.vcd_from, sc_core::SC_SEC),
                                            sc_core::sc_time(request.vcd_to, sc_core::SC_SEC));
    }
    if (request.receiver) cycle.receiver = request.receiver;
    cycle.free_running_clock = request.free_running_clock;
    cycle.sink_ready = request.sink_ready;
    Imager imager("imager", config, fidelity, light, result.log, result.vcd.get(), cycle);
    if (fidelity == Fidelity::Event) {
      imager.run_schedule(light, config.sim.threads);
    } else if (fidelity == Fidelity::Queue) {
      imager.run_queue(light);
    } else {
      // Every pixel stops scheduling itself past sim.duration and receivers stop their clocks
      // when idle, so the kernel starves exactly when the run (and any last handshake) is done.
      sc_core::sc_start();
    }
    imager.finish();
    result.facts.tau_s = imager.tau();
    const Imager::CycleStats cycle_stats = imager.cycle_stats();
    result.facts.protocol_violations = cycle_stats.protocol_violations;
    result.facts.receiver_clock_edges = cycle_stats.clock_edges;
    result.facts.scoreboard_mismatches = cycle_stats.scoreboard_mismatches;
    result.facts.scoreboard_beats = cycle_stats.scoreboard_beats;
    result.facts.multi_fire_steps = imager.multi_fire_steps();
    result.facts.empty_queue_frames = imager.empty_queue_frames();
  }
  result.log.finish();
  result.facts.fidelity = fidelity;
  result.facts.sim_time_s = config.sim.duration;
  result.facts.tick_s = fidelity == Fidelity::Cycle ? receiver_tick(config) : config.receiver.tick;
  result.facts.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace aesim
