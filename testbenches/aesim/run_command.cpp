#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "aesim/commands.hpp"
#include "config/data_dir.hpp"
#include "config/input_error.hpp"
#include "config/sensor_config.hpp"
#include "io/aedat.hpp"
#include "io/atomic_file.hpp"
#include "io/events_csv.hpp"
#include "io/image_file.hpp"
#include "recon/reconstruct.hpp"
#include "scene/photocurrents.hpp"
#include "scene/scene.hpp"
#include "top/imager_simulation.hpp"
#include "units/si_units.hpp"

namespace aesim {
namespace {

struct RunOptions {
  std::string sensor = "aloha";
  std::string scene;
  std::string duration;
  std::vector<std::string> sets;
  std::string out, csv, recon, vcd, summary;
};

// "pixel.c_int" -> "1e-13" for the AEDAT header, one line per key.
std::map<std::string, std::string> flatten(const nlohmann::json& sensor) {
  std::map<std::string, std::string> flat;
  for (const auto& [section, body] : sensor.items()) {
    for (const auto& [key, value] : body.items()) {
      flat[section + "." + key] = value.is_string() ? value.get<std::string>() : value.dump();
    }
  }
  return flat;
}

SensorConfig resolve_config(const RunOptions& opt, const SceneFiles& scene) {
  SensorConfig config = load_sensor(opt.sensor);
  apply_scene_settings(scene, config);
  for (const std::string& kv : opt.sets) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(fmt::format("--set '{}': expected section.key=value", kv));
    }
    config.set(kv.substr(0, eq), kv.substr(eq + 1));
  }
  if (!opt.duration.empty()) config.set("sim.duration", opt.duration);
  config.validate();
  return config;
}

int run(RunOptions opt) {
  const bool no_outputs_named = opt.out.empty() && opt.csv.empty() && opt.recon.empty() && opt.summary.empty();
  if (no_outputs_named) {
    opt.out = "out/events.aedat";
    opt.csv = "out/events.csv";
    opt.recon = "out/recon.png";
    opt.summary = "out/summary.json";
  }
  if (opt.scene.empty()) opt.scene = data_dir() + "/scenes/letters/A.pgm";
  const SceneFiles scene_files = find_scene(opt.scene);
  const SensorConfig config = resolve_config(opt, scene_files);
  if (!opt.vcd.empty()) {
    throw InputError("--vcd dumps the clocked bus signals, which need sim.fidelity=cycle (not modelled yet)");
  }
  if (!opt.recon.empty()) {
    try {
      check_image_path(opt.recon);
    } catch (const InputError&) {
      throw InputError(fmt::format("--recon '{}': use a .pgm or .png file name", opt.recon));
    }
  }
  if (!opt.out.empty() && config.sim.duration > 2147.0) {
    throw InputError("sim.duration: AEDAT 2.0 timestamps are int32 microseconds, so --out allows at most 2147 s");
  }

  const Scene scene = load_scene(scene_files, config);
  const Photocurrents light(scene, config.pixel);
  const SimulationResult result = simulate(config, light);
  const AddressMap map(config.array);

  OutputFiles files;
  const nlohmann::json summary = make_summary(config, result.log, result.facts);
  if (!opt.out.empty()) {
    write_aedat(files.open(opt.out), aedat_header(map, flatten(config.to_json())),
                aedat_records(result.log.events(), map, config.receiver.tick));
  }
  if (!opt.csv.empty()) write_events_csv(files.open(opt.csv), result.log.events(), config.receiver.tick);
  if (!opt.recon.empty()) {
    write_image(files.open(opt.recon), opt.recon,
                reconstruct(result.log.events(), map.cols(), map.rows(), ReconMode::Histogram));
  }
  if (!opt.summary.empty()) files.open(opt.summary) << summary.dump(2) << '\n';
  files.commit();

  const TileCounters total = result.log.totals();
  std::printf("aesim run: sensor %s, %dx%d pixels in %d tiles of %dx%d, scene %s (%dx%d%s)\n",
              opt.sensor.c_str(), map.cols(), map.rows(), map.tiles(), config.array.tile_cols,
              config.array.tile_rows, opt.scene.c_str(), scene.source_width, scene.source_height,
              scene.frames.size() > 1 ? fmt::format(", {} frames", scene.frames.size()).c_str() : "");
  std::printf("  simulated %s at fidelity %s, bus %s, in %.3g s wall time\n",
              format_si(config.sim.duration, "s").c_str(), to_string(result.facts.fidelity),
              to_string(config.bus.access), result.facts.wall_time_s);
  std::printf("  events: %llu fired (%s), %llu delivered, %llu collided, %llu dropped\n",
              static_cast<unsigned long long>(total.fired),
              format_si(static_cast<double>(total.fired) / config.sim.duration, "events/s").c_str(),
              static_cast<unsigned long long>(total.delivered), static_cast<unsigned long long>(total.collided),
              static_cast<unsigned long long>(total.dropped));
  std::string written;
  for (const std::string* path : {&opt.out, &opt.csv, &opt.recon, &opt.summary}) {
    if (!path->empty()) written += (written.empty() ? "" : ", ") + *path;
  }
  std::printf("  wrote %s\n", written.c_str());
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app, int& status) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Simulate a sensor looking at a scene; with no options, the aloha sensor on scenes/letters/A.pgm "
             "with all outputs under out/");
  cmd->add_option("--sensor", opt->sensor, "Sensor preset name (models/sensors/NAME.toml) or a .toml file")
      ->capture_default_str();
  cmd->add_option("--scene", opt->scene, "Scene: a .pgm/.pfm image or a folder of numbered frames");
  cmd->add_option("--duration", opt->duration, "Simulated time, e.g. 2s or 500ms (same as --set sim.duration=)");
  cmd->add_option("--set", opt->sets, "Override a parameter: section.key=value with SI units, e.g. pixel.c_int=50fF")
      ->allow_extra_args(false);
  cmd->add_option("--out", opt->out, "Events as AEDAT 2.0");
  cmd->add_option("--csv", opt->csv, "Events as CSV (t_us,x,y,tile,flags)");
  cmd->add_option("--recon", opt->recon, "Histogram reconstruction image (.png or .pgm)");
  cmd->add_option("--vcd", opt->vcd, "Bus waveforms (cycle fidelity)");
  cmd->add_option("--summary", opt->summary, "Summary JSON");
  cmd->callback([opt, &status] { status = run(*opt); });
}

}  // namespace aesim
