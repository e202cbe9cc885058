#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "compare/fidelity_errors.hpp"
#include "files/data_dir.hpp"
#include "errors/input_error.hpp"
#include "config/sensor_config.hpp"
#include "output/atomic_file.hpp"
#include "scene/photocurrents.hpp"
#include "scene/scene.hpp"
#include "run/imager_simulation.hpp"
#include "units/si_units.hpp"

namespace aesim {
namespace {

struct CompareOptions {
  std::string sensor = "aloha";
  std::vector<std::string> scenes;
  std::string duration = "500ms";
  std::vector<std::string> sets;
  std::vector<std::string> steps = {"1us", "10us", "100us", "1ms"};
  std::string output = "out/fidelity_ladder.csv";
  std::string max_events;
};

struct Rung {
  std::string name;
  Fidelity fidelity;
  ReceiverModel receiver = ReceiverModel::Reference;
  double step = 0;
};

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

int compare(CompareOptions opt) {
  if (opt.scenes.empty()) opt.scenes = {data_dir() + "/scenes/letters/A.pgm"};
  std::vector<Rung> rungs = {{"queue", Fidelity::Queue},
                             {"event", Fidelity::Event},
                             {"pixel_processes", Fidelity::PixelProcesses},
                             {"cycle", Fidelity::Cycle},
                             {"cycle_rtl", Fidelity::Cycle, ReceiverModel::Rtl}};
  for (const std::string& s : opt.steps) {
    rungs.push_back({"fixed_step", Fidelity::FixedStep, ReceiverModel::Reference, parse_si(s, "s", "--steps")});
  }
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
    base.apply_overrides(opt.sets);
    base.set("sim.duration", opt.duration);
    if (!opt.max_events.empty()) base.set("sim.max_events", opt.max_events);
    base.validate();
    base = base.resolved();
    const Scene scene = load_scene(files, base);
    const Photocurrents light(scene, base.pixel);
    const Image mean = mean_frame(scene, base.sim.duration);

    SensorConfig ref_config = base;
    ref_config.sim.fidelity = Fidelity::Event;
    SimulationRequest request;
    request.keep_truth = true;
    const SimulationResult reference = simulate(ref_config, light, request);
    const std::size_t first = rows.size();
    for (const Rung& rung : rungs) {
      SensorConfig c = base;
      c.sim.fidelity = rung.fidelity;
      c.receiver.model = rung.receiver;
      if (rung.step > 0) c.sim.step = rung.step;
      c.validate();
      const SimulationResult r = simulate(c, light, request);
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
    // Pareto front on (wall time per simulated second, RMS firing-time error): no other rung of
    // this scene is at least as fast and as accurate, and better in one.
    for (std::size_t i = first; i < rows.size(); ++i) {
      rows[i].pareto = std::none_of(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.end(), [&](const Row& o) {
        const Row& r = rows[i];
        return o.wall_per_sim <= r.wall_per_sim && o.errors.rms_time_error_s <= r.errors.rms_time_error_s &&
               (o.wall_per_sim < r.wall_per_sim || o.errors.rms_time_error_s < r.errors.rms_time_error_s);
      });
    }
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
  fmt::print("aesim compare: {} rungs on {} scenes -> {}\n", rungs.size(), opt.scenes.size(), opt.output);
  return 0;
}

}  // namespace

void add_compare_command(CLI::App& app, int& status) {
  auto opt = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run every fidelity rung on the same scenes and sensor and measure each against the event rung");
  cmd->add_option("--sensor", opt->sensor, "Sensor preset or .toml file")->capture_default_str();
  cmd->add_option("--scene", opt->scenes, "Scene file or folder (repeatable; default scenes/letters/A.pgm)");
  cmd->add_option("--duration", opt->duration, "Simulated time per run")->capture_default_str();
  cmd->add_option("--set", opt->sets, "Override a parameter for every rung: section.key=value");
  cmd->add_option("--steps", opt->steps, "Steps of the fixed_step baseline")->delimiter(',')->capture_default_str();
  cmd->add_option("-o,--output", opt->output, "CSV file")->capture_default_str();
  cmd->add_option("--max-events", opt->max_events, "The most work one run may ask for (default 1e8 fired events)");
  cmd->callback([opt, &status] { status = compare(*opt); });
}

}  // namespace aesim
