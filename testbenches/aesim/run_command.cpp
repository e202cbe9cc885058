#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_settings.hpp"
#include "commands.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/event_files/events_csv.hpp"
#include "aesim/images/image_file.hpp"
#include "aesim/event_files/truth_csv.hpp"
#include "aesim/recon/reconstruct.hpp"
#include "aesim/scene/calibrated_range.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/summary/summary.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {

int run_command(RunOptions opt) {
  const bool no_outputs_named = opt.out.empty() && opt.csv.empty() && opt.recon.empty() && opt.summary.empty();
  if (no_outputs_named) {
    opt.out = "out/events.aedat";
    opt.csv = "out/events.csv";
    opt.recon = "out/recon.png";
    opt.summary = "out/summary.json";
  }
  // The default scene is named as the README names it, wherever the tree is.
  const bool default_scene = opt.scene.empty();
  if (default_scene) opt.scene = default_scene_path();
  const SceneFiles scene_files = find_scene(opt.scene);
  const ResolvedConfig config =
      configure_run(load_sensor(opt.sensor), scene_files, command_settings(opt.sets, opt.duration, opt.max_events));
  SimulationRequest request;
  request.keep_truth = !opt.truth.empty();
  request.waveforms = !opt.vcd.empty();
  if (request.waveforms) {
    request.vcd_from = parse_si(opt.vcd_from, "s", "--vcd-from");
    request.vcd_to = opt.vcd_to.empty() ? config.sim.duration : parse_si(opt.vcd_to, "s", "--vcd-to");
    if (!(request.vcd_from >= 0 && request.vcd_from < config.sim.duration && request.vcd_to > request.vcd_from)) {
      throw InputError("--vcd-from/--vcd-to: need 0 <= from < to and from < sim.duration");
    }
    request.vcd_to = std::min(request.vcd_to, config.sim.duration);
  }
  const Fidelity fidelity = choose_rung(config, request).fidelity();
  if (!opt.recon.empty()) {
    try {
      check_image_path(opt.recon);
    } catch (const InputError&) {
      throw InputError(fmt::format("--recon '{}': use a .pgm or .png file name", opt.recon));
    }
  }
  const AddressMap map(config.array);
  const AedatLayout layout = parse_aedat_layout(opt.aedat_layout);
  const Aedat4Compression compression = parse_aedat4_compression(opt.aedat4_compression);
  if (!opt.out.empty()) {
    const EventFormatRow& row = event_format_of(opt.out, "--out");
    if (!row.open) throw InputError(fmt::format("--out '{}': write events CSV with --csv", opt.out));
    if (row.longest_run > 0 && config.sim.duration > row.longest_run) {
      throw InputError(fmt::format("sim.duration: {}, so an {} --out allows at most {} s", row.stamps, row.name,
                                   row.longest_run));
    }
    if (layout != AedatLayout::Aesim && row.format != EventFileFormat::Aedat2) {
      throw InputError(fmt::format("--aedat-layout {}: jAER's layouts are for AEDAT 2.0 (.aedat) files", opt.aedat_layout));
    }
    jaer_chip(layout, map);  // an array the chip cannot hold is refused before the run
  }
  std::vector<std::string> rtl_traces;
  if (request.waveforms && fidelity == Fidelity::Cycle && config.receiver.model == ReceiverModel::Rtl) {
    const std::string stem = opt.vcd.size() > 4 && opt.vcd.substr(opt.vcd.size() - 4) == ".vcd"
                                 ? opt.vcd.substr(0, opt.vcd.size() - 4)
                                 : opt.vcd;
    for (int t = 0; t < map.tiles(); ++t) rtl_traces.push_back(fmt::format("{}.tile{}.rtl.vcd", stem, t));
  }
  // Every output is checked before the run, so that a bad path costs no simulation and leaves nothing.
  std::vector<OutputPath> outputs = {{"--out", opt.out},     {"--csv", opt.csv},     {"--recon", opt.recon},
                                     {"--summary", opt.summary}, {"--truth", opt.truth}, {"--vcd", opt.vcd}};
  for (const std::string& trace : rtl_traces) outputs.push_back({"--vcd (RTL trace)", trace});
  std::vector<std::string> inputs = scene_files.frames;
  inputs.push_back(scene_files.settings);
  inputs.push_back(opt.sensor);
  check_output_paths(outputs, inputs);

  const Photocurrents photocurrents(load_scene(scene_files, config.array, config.scene, config.sim.duration), config.pixel);
  const Scene& scene = photocurrents.scene();
  OutputFiles files;
  if (!rtl_traces.empty()) {
    // Verilator writes these during the run; they are renamed into place with the rest.
    std::vector<std::string> temps;
    for (const std::string& trace : rtl_traces) temps.push_back(files.adopt(trace));
    request.rtl_trace_path = [temps](int tile) { return temps[static_cast<std::size_t>(tile)]; };
  }
  // The event files are written while the run goes (into temporary files, renamed by commit()).
  const double tick = choose_rung(config, request).tick(config);
  EventStreams writers;
  std::unique_ptr<EventFileWriter> events;
  std::unique_ptr<EventsCsvWriter> csv;
  std::unique_ptr<TruthCsvWriter> truth;
  if (!opt.out.empty()) {
    EventFileSpec spec;
    spec.array = config.array;
    spec.sensor = sensor_metadata(config.to_json());
    spec.tick = tick;
    spec.duration = config.sim.duration;
    spec.layout = layout;
    spec.compression = compression;
    events = open_event_writer(files, opt.out, spec);
    writers.add(*events);
  }
  if (!opt.csv.empty()) {
    csv = std::make_unique<EventsCsvWriter>(files.open(opt.csv), tick);
    writers.add(*csv);
  }
  if (!opt.truth.empty()) {
    truth = std::make_unique<TruthCsvWriter>(files.open(opt.truth));
    writers.add(*truth);
  }
  request.keep_events = events || csv;
  request.stream = &writers;
  const SimulationResult result = simulate(config, photocurrents, request);
  if (events) events->finish();
  if (csv) csv->flush();
  if (truth) truth->flush();

  const Image mean = mean_frame(scene, config.sim.duration);
  const nlohmann::json summary = make_summary(config, result.log, result.facts, &mean);
  if (!opt.recon.empty()) {
    write_image(files.open(opt.recon), opt.recon, histogram_image(result.log.output_per_pixel(), map.cols(), map.rows()));
  }
  if (!opt.summary.empty()) files.open(opt.summary) << summary.dump(2) << '\n';
  if (!opt.vcd.empty()) result.vcd->write(files.open(opt.vcd));
  files.commit();

  const TileCounters total = result.log.totals();
  const std::string range = calibrated_range_warning(calibrated_range_use(scene, config.pixel), config.pixel);
  if (!range.empty()) std::fprintf(stderr, "aesim: warning: %s\n", range.c_str());
  if (events && !events->reader_warning().empty()) {
    std::fprintf(stderr, "aesim: warning: %s: %s\n", opt.out.c_str(), events->reader_warning().c_str());
  }
  if (events && events->off_array() > 0) {
    std::fprintf(stderr,
                 "aesim: warning: %llu ghost events name no pixel (the OR of colliding addresses, past their tile's "
                 "columns or rows); %s leaves them out (no reader could place them); the events CSV keeps them\n",
                 static_cast<unsigned long long>(events->off_array()), opt.out.c_str());
  }
  if (result.facts.empty_queue_frames > 0) {
    std::fprintf(stderr,
                 "aesim: warning: %llu lit frames are too short for the queue model's brightest pixel to fire once "
                 "(f_max * P_max * T_frame < 1/2): they produced no events\n",
                 static_cast<unsigned long long>(result.facts.empty_queue_frames));
  }
  if (result.facts.multi_fire_steps > 0) {
    std::fprintf(stderr,
                 "aesim: warning: sim.step=%s is coarser than some pixels' integration time (%llu steps with "
                 "several firings): their firing times are quantised to the step\n",
                 format_si(config.sim.step, "s").c_str(), static_cast<unsigned long long>(result.facts.multi_fire_steps));
  }
  std::printf("aesim run: sensor %s, %dx%d pixels in %d tiles of %dx%d, scene %s (%dx%d%s%s)\n",
              opt.sensor.c_str(), map.cols(), map.rows(), map.tiles(), config.array.tile_cols,
              config.array.tile_rows, default_scene ? kDefaultScene : opt.scene.c_str(),
              scene.source_width, scene.source_height,
              scene.frames.size() > 1 ? fmt::format(", {} frames", scene.frames.size()).c_str() : "",
              default_scene ? ", the default" : "");
  std::printf("  simulated %s at fidelity %s%s, bus %s (tau %s%s), in %.3g s wall time\n",
              format_si(config.sim.duration, "s").c_str(), to_string(fidelity),
              config.sim.fidelity == Fidelity::Auto ? " (chosen by auto)" : "", to_string(config.bus.access),
              format_si(result.facts.tau_s, "s").c_str(), fidelity == Fidelity::Cycle ? " measured" : "",
              result.facts.wall_time_s);
  std::printf("  events: %llu fired (%s), %llu delivered, %llu lost to collisions (%.2f %%), %llu ghosts\n",
              static_cast<unsigned long long>(total.fired),
              format_si(static_cast<double>(total.fired) / config.sim.duration, "events/s").c_str(),
              static_cast<unsigned long long>(total.delivered), static_cast<unsigned long long>(total.collided),
              100.0 * total.collision_fraction(),
              static_cast<unsigned long long>(total.ghost));
  std::printf("  bus load per tile: G = %.4g offered, S = %.4g delivered\n", summary["offered_load"].get<double>(),
              summary["throughput"].get<double>());
  // The figures a pixel is sized by (docs/sizing.md), which otherwise sit only in the summary.
  const auto figure = [&summary](const char* key) {
    const nlohmann::json& v = summary[key];
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  const double psnr = figure("psnr_db");
  std::printf("  sizing: power %s (%s per tile, %s of it static), PSNR %s and %.1f %% of pixels firing %d+ times "
              "within the %s readout window\n",
              format_si(figure("power_w"), "W").c_str(), format_si(figure("power_per_tile_w"), "W").c_str(),
              format_si(figure("power_static_w"), "W").c_str(),
              std::isfinite(psnr) ? fmt::format("{:.1f} dB", psnr).c_str()
              : std::isinf(psnr)  ? "infinite (the reconstruction equals the scene)"
                                  : "not computed",
              100.0 * figure("dynamic_range_covered"), config.analysis.min_events,
              format_si(config.analysis.window, "s").c_str());
  std::string written;
  for (const std::string* path : {&opt.out, &opt.csv, &opt.recon, &opt.summary, &opt.truth, &opt.vcd}) {
    if (!path->empty()) written += (written.empty() ? "" : ", ") + *path;
  }
  if (!rtl_traces.empty()) written += fmt::format(" (and RTL internals in {} .. tile{}.rtl.vcd)", rtl_traces.front(), rtl_traces.size() - 1);
  std::printf("  wrote %s\n", written.c_str());
  return 0;
}

}  // namespace aesim
