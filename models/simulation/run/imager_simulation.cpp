#include "aesim/run/imager_simulation.hpp"

#include <chrono>

#include "aesim/rungs/run_budget.hpp"

namespace aesim {

SimulationResult simulate(const ResolvedConfig& config, const Photocurrents& photocurrents,
                          const SimulationRequest& request) {
  const Rung& rung = choose_rung(config, request);
  check_work(config, photocurrents, rung.fidelity());
  const auto wall_start = std::chrono::steady_clock::now();

  const AddressMap map(config.array);
  SimulationResult result{EventLog(map.tiles(), LogOutputs{request.keep_events, request.keep_truth, request.stream}), {}, nullptr};
  result.log.count_pixels(map, config.analysis.window);
  if (request.waveforms) result.vcd = std::make_unique<VcdRecorder>(request.vcd_from, request.vcd_to);
  rung.run(RungRun{config, photocurrents, map, request, result.log, result.vcd.get()}, result.facts);
  result.log.finish();
  result.facts.fidelity = rung.fidelity();
  result.facts.sim_time_s = config.sim.duration;
  result.facts.tick_s = rung.tick(config);
  result.facts.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace aesim
