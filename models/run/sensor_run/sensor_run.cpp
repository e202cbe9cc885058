#include "aesim/sensor_run/sensor_run.hpp"

#include <algorithm>
#include <memory>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/event_files/events_csv.hpp"
#include "aesim/event_files/truth_csv.hpp"
#include "aesim/images/image_file.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/recon/reconstruct.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/scene/calibrated_range.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/summary/summary.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

// The VCD's window, checked against the run: 0 <= from < to, from < sim.duration, to clipped to it.
void set_vcd_window(const RunSpec& spec, double duration, SimulationRequest& request) {
  request.waveforms = true;
  request.vcd_from = parse_si(spec.vcd_from, "s", "--vcd-from");
  request.vcd_to = spec.vcd_to.empty() ? duration : parse_si(spec.vcd_to, "s", "--vcd-to");
  if (!(request.vcd_from >= 0 && request.vcd_from < duration && request.vcd_to > request.vcd_from)) {
    throw InputError("--vcd-from/--vcd-to: need 0 <= from < to and from < sim.duration");
  }
  request.vcd_to = std::min(request.vcd_to, duration);
}

// An event file's format, checked against the run before it starts.
void check_event_file(const RunSpec& spec, const ResolvedConfig& config, AedatLayout layout) {
  const EventFormatRow& row = writable_event_format(spec.out, "--out");
  if (row.longest_run > 0 && config.sim.duration > row.longest_run) {
    throw InputError(fmt::format("sim.duration: {}, so {} written by --out holds at most {} s", row.stamps, row.name,
                                 row.longest_run));
  }
  if (layout != AedatLayout::Aesim && row.format != EventFileFormat::Aedat2) {
    throw InputError(fmt::format("--aedat-layout {}: jAER's layouts are for AEDAT 2.0 (.aedat) files", spec.aedat_layout));
  }
  jaer_chip(layout, AddressMap(config.array));  // an array the chip cannot hold is refused before the run
}

// One file per tile for the RTL's internal signals, beside the VCD: STEM.tile<t>.rtl.vcd.
std::vector<std::string> rtl_trace_paths(const std::string& vcd, int tiles) {
  const bool has_extension = vcd.size() > 4 && vcd.compare(vcd.size() - 4, 4, ".vcd") == 0;
  const std::string stem = has_extension ? vcd.substr(0, vcd.size() - 4) : vcd;
  std::vector<std::string> paths;
  for (int t = 0; t < tiles; ++t) paths.push_back(fmt::format("{}.tile{}.rtl.vcd", stem, t));
  return paths;
}

// What the run's facts and writers ask the user to know.
std::vector<std::string> run_warnings(const RunSpec& spec, const ResolvedConfig& config, const Scene& scene,
                                      const RunFacts& facts, const EventFileWriter* events) {
  std::vector<std::string> warnings;
  const std::string range = calibrated_range_warning(calibrated_range_use(scene, config.pixel), config.pixel);
  if (!range.empty()) warnings.push_back(range);
  if (events && !events->reader_warning().empty()) {
    warnings.push_back(fmt::format("{}: {}", spec.out, events->reader_warning()));
  }
  if (events && events->off_array() > 0) {
    warnings.push_back(fmt::format(
        "{} ghost events name no pixel (the OR of colliding addresses, past their tile's columns or rows); {} leaves "
        "them out (no reader could place them); the events CSV keeps them",
        events->off_array(), spec.out));
  }
  if (facts.empty_queue_frames > 0) {
    warnings.push_back(fmt::format(
        "{} lit frames are too short for the queue model's brightest pixel to fire once (f_max * P_max * T_frame < "
        "1/2): they produced no events",
        facts.empty_queue_frames));
  }
  if (facts.multi_fire_steps > 0) {
    warnings.push_back(fmt::format(
        "sim.step={} is coarser than some pixels' integration time ({} steps with several firings): their firing "
        "times are quantised to the step",
        format_si(config.sim.step, "s"), facts.multi_fire_steps));
  }
  return warnings;
}

}  // namespace

RunReport run_sensor(const RunSpec& spec) {
  const bool in_memory = !spec.frames.empty();
  const bool default_scene = !in_memory && spec.scene.empty();
  const SceneFiles scene_files = in_memory ? SceneFiles{} : find_scene(default_scene ? default_scene_path() : spec.scene);
  const ResolvedConfig config = configure_run(load_sensor(spec.sensor), scene_files, spec.settings);

  SimulationRequest request;
  request.keep_truth = !spec.truth.empty() || spec.keep_truth;
  if (!spec.vcd.empty()) set_vcd_window(spec, config.sim.duration, request);
  const Rung& rung = choose_rung(config, request);
  if (!spec.recon.empty()) {
    try {
      check_image_path(spec.recon);
    } catch (const InputError&) {
      throw InputError(fmt::format("--recon '{}': use a .pgm or .png file name", spec.recon));
    }
  }
  const AddressMap map(config.array);
  const AedatLayout layout = parse_aedat_layout(spec.aedat_layout);
  const Aedat4Compression compression = parse_aedat4_compression(spec.aedat4_compression);
  const RawEncoding raw_encoding = parse_raw_encoding(spec.raw_encoding);
  if (!spec.out.empty()) check_event_file(spec, config, layout);
  const std::vector<std::string> rtl_traces =
      request.waveforms && rung.fidelity() == Fidelity::Cycle && config.receiver.model == ReceiverModel::Rtl
          ? rtl_trace_paths(spec.vcd, map.tiles())
          : std::vector<std::string>{};
  // Every output is checked before the run, so that a bad path costs no simulation and leaves nothing.
  std::vector<OutputPath> outputs = {{"--out", spec.out},         {"--csv", spec.csv},     {"--recon", spec.recon},
                                     {"--summary", spec.summary}, {"--truth", spec.truth}, {"--vcd", spec.vcd}};
  for (const std::string& trace : rtl_traces) outputs.push_back({"--vcd (RTL trace)", trace});
  std::vector<std::string> inputs = scene_files.frames;
  inputs.push_back(scene_files.settings);
  inputs.push_back(spec.sensor);
  check_output_paths(outputs, inputs);

  const Photocurrents photocurrents(in_memory ? load_scene(spec.frames, config.array, config.scene)
                                              : load_scene(scene_files, config.array, config.scene, config.sim.duration),
                                    config.pixel);
  const Scene& scene = photocurrents.scene();
  OutputFiles files;
  if (!rtl_traces.empty()) {
    // Verilator writes these during the run; they are renamed into place with the rest.
    std::vector<std::string> temps;
    for (const std::string& trace : rtl_traces) temps.push_back(files.adopt(trace));
    request.rtl_trace_path = [temps](int tile) { return temps[static_cast<std::size_t>(tile)]; };
  }
  // The event files are written while the run goes (into temporary files, renamed by commit()).
  const double tick = rung.tick(config);
  EventStreams streams;
  std::unique_ptr<EventFileWriter> events;
  std::unique_ptr<EventsCsvWriter> csv;
  std::unique_ptr<TruthCsvWriter> truth;
  if (!spec.out.empty()) {
    EventFileSpec file;
    file.array = config.array;
    file.sensor = sensor_metadata(config.to_json());
    file.tick = tick;
    file.duration = config.sim.duration;
    file.layout = layout;
    file.compression = compression;
    file.raw_encoding = raw_encoding;
    events = open_event_writer(files, spec.out, file);
    streams.add(*events);
  }
  if (!spec.csv.empty()) {
    csv = std::make_unique<EventsCsvWriter>(files.open(spec.csv), tick);
    streams.add(*csv);
  }
  if (!spec.truth.empty()) {
    truth = std::make_unique<TruthCsvWriter>(files.open(spec.truth));
    streams.add(*truth);
  }
  if (spec.stream) streams.add(*spec.stream);
  request.keep_events = events || csv || spec.stream;
  request.stream = &streams;
  const SimulationResult result = simulate(config, photocurrents, request);
  if (events) events->finish();
  if (csv) csv->flush();
  if (truth) truth->flush();

  RunReport report(config);
  const Image mean = mean_frame(scene, config.sim.duration);
  report.summary = make_summary(config, result.log, result.facts, &mean);
  if (!spec.recon.empty()) {
    write_image(files.open(spec.recon), spec.recon, histogram_image(result.log.output_per_pixel(), map.cols(), map.rows()));
  }
  if (!spec.summary.empty()) files.open(spec.summary) << report.summary.dump(2) << '\n';
  if (!spec.vcd.empty()) result.vcd->write(files.open(spec.vcd));
  files.commit();

  report.warnings = run_warnings(spec, config, scene, result.facts, events.get());
  report.fidelity = rung.fidelity();
  report.tick = tick;
  report.scene = default_scene ? kDefaultScene : in_memory ? "(frames in memory)" : scene_files.source;
  report.default_scene = default_scene;
  report.scene_width = scene.source_width;
  report.scene_height = scene.source_height;
  report.scene_frames = scene.frames.size();
  report.totals = result.log.totals();
  report.facts = result.facts;
  for (const std::string* path : {&spec.out, &spec.csv, &spec.recon, &spec.summary, &spec.truth, &spec.vcd}) {
    if (!path->empty()) report.written.push_back(*path);
  }
  report.rtl_traces = rtl_traces;
  return report;
}

}  // namespace aesim
