#include "aesim/embed/imager.hpp"

#include <optional>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/rungs/cycle_array.hpp"
#include "aesim/rungs/run_budget.hpp"
#include "aesim/scene/calibrated_range.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/tile/cycle_tile.hpp"

namespace aesim {

// What the array's modules refer to for the whole simulation, made before them.
struct Imager::Run {
  ResolvedConfig config;
  Photocurrents photocurrents;
  AddressMap map;
  SimulationRequest request;
  EventLog log;
};

SpecInputs spec_inputs(const ImagerSpec& spec, Fidelity rung, const char* use_instead, const char* report_id) {
  const SceneFiles scene = find_scene(spec.scene.empty() ? default_scene_path() : spec.scene);
  ResolvedConfig config = configure_run(load_sensor(spec.sensor), scene, spec.settings);
  if (config.sim.fidelity != rung && config.sim.fidelity != Fidelity::Auto) {
    throw InputError(fmt::format("sim.fidelity={}: {}", to_string(config.sim.fidelity), use_instead));
  }
  config.sim.fidelity = rung;
  rung_for(rung).check(config);
  Photocurrents photocurrents(load_scene(scene, config.array, config.scene, config.sim.duration), config.pixel);
  const std::string range =
      calibrated_range_warning(calibrated_range_use(photocurrents.scene(), config.pixel), config.pixel);
  if (!range.empty()) SC_REPORT_WARNING(report_id, range.c_str());
  return {std::move(config), std::move(photocurrents)};
}

Imager::Imager(const sc_core::sc_module_name& name, const ImagerSpec& spec) : sc_module(name), tile("tile") {
  SpecInputs in = spec_inputs(spec, Fidelity::Cycle, "an Imager is the cycle fidelity (use simulate() for the others)",
                              "aesim/Imager");
  check_work(in.config, in.photocurrents, Fidelity::Cycle);
  check_time_resolution(in.config.receiver);
  const AddressMap map(in.config.array);
  for (const std::uint32_t t : spec.outside_receivers) {
    if (t >= static_cast<std::uint32_t>(map.tiles())) {
      throw InputError(fmt::format("ImagerSpec::outside_receivers names tile {}, but the sensor has {} tiles (0 to {})",
                                   t, map.tiles(), map.tiles() - 1));
    }
  }
  run_.reset(new Run{std::move(in.config), std::move(in.photocurrents), map, SimulationRequest{},
                     EventLog(map.tiles(), LogOutputs{true, false, nullptr})});
  run_->log.count_pixels(run_->map, run_->config.analysis.window);
  run_->request.cycle.receiver = spec.receiver;
  run_->request.cycle.outside_receivers = spec.outside_receivers;
  const RungRun rung_run{run_->config, run_->photocurrents, run_->map, run_->request, run_->log, nullptr};
  array_ = std::make_unique<CycleArray>("array", rung_run, cycle_options(rung_run));
  tile.init(array_->tiles().size());
  for (std::size_t t = 0; t < tile.size(); ++t) {
    tile[t].attach(*array_->tiles()[t], static_cast<std::uint32_t>(t), run_->config.sim.duration);
  }
}

Imager::~Imager() = default;

const ResolvedConfig& Imager::config() const { return run_->config; }

double Imager::tick() const { return rung_for(Fidelity::Cycle).tick(run_->config); }

ReceiverCycleModel::Config Imager::receiver_config() const {
  return receiver_model_config(run_->config.receiver, run_->config.bus.contention_detect, run_->request.cycle);
}

void Imager::trace(sc_core::sc_trace_file* file) const {
  for (std::size_t t = 0; t < array_->tiles().size(); ++t) {
    array_->tiles()[t]->trace_wires(file, fmt::format("{}.tile{}.", name(), t));
  }
}

void Imager::finish() {
  if (finished_) return;
  if (sc_core::sc_get_status() == sc_core::SC_ELABORATION) {
    throw InputError("Imager::events(): the simulation has not run yet (call sc_start() first)");
  }
  // Read early, the record would stop there and lose what is still to come.
  if (!array_->done()) {
    throw InputError(fmt::format("Imager::events(): the run is not done at {} (sim.duration {} s): a firing or a "
                                 "handshake is still to come; call sc_start() further first",
                                 sc_core::sc_time_stamp().to_string(), run_->config.sim.duration));
  }
  run_->log.finish();
  finished_ = true;
}

const std::vector<AddressEvent>& Imager::events() {
  finish();
  return run_->log.events();
}

std::uint64_t Imager::protocol_violations() const {
  std::uint64_t n = 0;
  for (const auto& tile : array_->tiles()) n += tile->stats().protocol_violations;
  return n;
}

std::vector<TileCounters> Imager::tiles() {
  finish();
  return run_->log.tiles();
}

}  // namespace aesim
