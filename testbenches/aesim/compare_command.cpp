#include <cmath>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command_settings.hpp"
#include "commands.hpp"
#include "aesim/compare/fidelity_errors.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/pareto/pareto_front.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace {

// One rung of the ladder as compare runs it: a rung of the table, with a receiver model and a step
// where the rung has them.
struct LadderStep {
  std::string name;
  Fidelity fidelity;
  ReceiverModel receiver = ReceiverModel::Reference;
  double step = 0;
};

// Every rung of the table; a rung with a receiver model with each receiver (the RTL one as
// NAME_rtl), a stepped rung at each of `steps`.
std::vector<LadderStep> ladder(const std::vector<double>& steps) {
  std::vector<LadderStep> out;
  for (const Rung* rung : rung_table()) {
    const RungCapabilities can = rung->capabilities();
    const std::string name = to_string(rung->fidelity());
    if (can.stepped) {
      for (double step : steps) out.push_back({name, rung->fidelity(), ReceiverModel::Reference, step});
      continue;
    }
    out.push_back({name, rung->fidelity()});
    if (can.receiver_model) out.push_back({name + "_rtl", rung->fidelity(), ReceiverModel::Rtl});
  }
  return out;
}

struct Row {
  std::string scene, rung;
  double step = 0, wall = 0, wall_per_sim = 0;
  std::uint64_t fired = 0;
  FidelityErrors errors;
  bool pareto = false;
};

std::string display(const std::string& path) {
  const std::string root = data_dir() + "/";
  return path.rfind(root, 0) == 0 ? path.substr(root.size()) : path;
}

}  // namespace

int compare_command(CompareOptions opt) {
  if (opt.scenes.empty()) opt.scenes = {default_scene_path()};
  std::vector<double> steps;
  for (const std::string& text : opt.steps) {
    steps.push_back(parse_si(text, "s", "--steps"));
    if (!(steps.back() > 0) || !std::isfinite(steps.back())) throw InputError(fmt::format("--steps: '{}' is not a positive time", text));
  }
  const std::vector<LadderStep> rungs = ladder(steps);
  std::vector<std::string> inputs = {opt.sensor};
  for (const std::string& scene_path : opt.scenes) {
    const SceneFiles files = find_scene(scene_path);
    inputs.insert(inputs.end(), files.frames.begin(), files.frames.end());
    inputs.push_back(files.settings);
  }
  check_output_paths({{"-o", opt.output}}, inputs);
  std::vector<Row> rows;
  for (const std::string& scene_path : opt.scenes) {
    const SceneFiles files = find_scene(scene_path);
    SensorConfig base = load_sensor(opt.sensor);
    apply_scene_settings(files, base);
    for (const Setting& setting : command_settings(opt.sets, opt.duration, opt.max_events)) {
      base.set(setting.first, setting.second);
    }
    const ResolvedConfig resolved = base.resolved();
    const Photocurrents photocurrents(load_scene(files, resolved.array, resolved.scene, resolved.sim.duration),
                                      resolved.pixel);
    const Image mean = mean_frame(photocurrents.scene(), resolved.sim.duration);

    SensorConfig ref_config = base;
    ref_config.sim.fidelity = Fidelity::Event;
    SimulationRequest request;
    request.keep_truth = true;
    const SimulationResult reference = simulate(ref_config.resolved(), photocurrents, request);
    const std::size_t first = rows.size();
    for (const LadderStep& rung : rungs) {
      SensorConfig c = base;
      c.sim.fidelity = rung.fidelity;
      c.receiver.model = rung.receiver;
      if (rung.step > 0) c.sim.step = rung.step;
      const SimulationResult r = simulate(c.resolved(), photocurrents, request);
      Row row;
      row.scene = display(scene_path);
      row.rung = rung.name;
      row.step = rung.step;
      row.wall = r.facts.wall_time_s;
      row.wall_per_sim = r.facts.wall_time_s / c.sim.duration;
      row.fired = r.log.totals().fired;
      row.errors = fidelity_errors(reference.log, r.log, mean);
      rows.push_back(row);
      std::fprintf(stderr, "aesim compare: %s %s%s: %.3g s wall, count error %.3g, rms time error %.3g s\n",
                   row.scene.c_str(), row.rung.c_str(),
                   rung.step > 0 ? (" " + format_si(rung.step, "s")).c_str() : "", row.wall, row.errors.count_error,
                   row.errors.rms_time_error_s);
    }
    // Pareto front on (wall time per simulated second, RMS firing-time error) among this scene's rungs.
    std::vector<std::pair<double, double>> scores;
    for (std::size_t i = first; i < rows.size(); ++i) scores.emplace_back(rows[i].wall_per_sim, rows[i].errors.rms_time_error_s);
    for (std::size_t k : pareto_front(scores)) rows[first + k].pareto = true;
  }
  OutputFiles files;
  std::ostream& csv = files.open(opt.output);
  csv << "scene,rung,step_s,wall_time_s,wall_per_sim_s,events_fired,count_error,rms_time_error_s,"
         "collision_fraction,collision_fraction_error,psnr_db,pareto\n";
  for (const Row& r : rows) {
    csv << fmt::format("{},{},{:.9g},{:.6g},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.4f},{}\n", r.scene, r.rung, r.step,
                       r.wall, r.wall_per_sim, r.fired, r.errors.count_error, r.errors.rms_time_error_s,
                       r.errors.collision_fraction, r.errors.collision_fraction_error, r.errors.psnr_db,
                       r.pareto ? 1 : 0);
  }
  files.commit();
  fmt::print(report_stream(), "aesim compare: {} rungs on {} scenes -> {}\n", rungs.size(), opt.scenes.size(), opt.output);
  return 0;
}

}  // namespace aesim
