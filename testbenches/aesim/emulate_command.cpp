#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "aesim/array/address_map.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/emulator/emulator.hpp"
#include "aesim/scene/y4m_video.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/images/image_file.hpp"
#include "aesim/recon/reconstruct.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace {

void check_probability(double p, const char* name) {
  if (!(p >= 0 && p <= 1)) throw InputError(fmt::format("{}: a probability from 0 to 1 (got {})", name, p));
}

}  // namespace

EmulatedRun emulate_frames(const EmulateOptions& opt, std::vector<Image> given) {
  EmulatedRun out;
  EmulatorSettings& s = out.settings;
  s.behaviour = parse_behaviour(opt.behaviour);
  if (!(opt.threshold >= 0 && opt.threshold <= 255)) throw InputError("--threshold: a grey level from 0 to 255");
  s.threshold = opt.threshold / 255.0;
  int low = 0, high = 255;
  if (std::sscanf(opt.clip.c_str(), "%d,%d", &low, &high) != 2 || low < 0 || high > 255 || low > high) {
    throw InputError(fmt::format("--clip: expected LOW,HIGH grey levels with 0 <= LOW <= HIGH <= 255 (got '{}')", opt.clip));
  }
  s.clip_low = low / 255.0;
  s.clip_high = high / 255.0;
  if (!opt.size.empty()) {
    const ArraySize size = parse_array_size(opt.size, "--size");
    s.width = size.width;
    s.height = size.height;
  }
  if (!(opt.f_max > 0 && opt.f_max <= 1e6)) throw InputError("--f-max: events per frame at full scale, from >0 to 1e6");
  check_probability(opt.chaos_in, "--chaos-in");
  check_probability(opt.chaos_out, "--chaos-out");
  if (!(opt.frame_rate >= 0 && opt.frame_rate <= kMaxFrameRate)) {
    throw InputError(fmt::format("--frame-rate: must be positive, finite and at most {:g} Hz", kMaxFrameRate));
  }
  if (!(opt.max_events >= 1 && opt.max_events <= 1e15)) throw InputError("--max-events: must be from 1 to 1e15");
  if (opt.events < 0) throw InputError("--events: must not be negative");
  if (opt.spread != "even" && opt.spread != "literal") {
    throw InputError(fmt::format("--spread: expected even or literal (got '{}')", opt.spread));
  }
  s.spread = opt.spread == "even" ? QueueSpread::Even : QueueSpread::Literal;
  s.f_max = opt.f_max;
  s.chaos_in = opt.chaos_in;
  s.chaos_out = opt.chaos_out;
  s.seed = opt.seed;
  s.max_events = opt.max_events;

  std::vector<Image>& frames = out.frames;
  double rate = 25;
  if (!given.empty()) {
    frames = std::move(given);
  } else if (file_extension(opt.input) == ".y4m") {
    Y4mVideo video = read_y4m(opt.input);
    frames = std::move(video.frames);
    rate = video.frame_rate;
  } else {
    const SceneFiles files = find_scene(opt.input);
    SensorConfig c;
    apply_scene_settings(files, c);
    rate = c.scene.frame_rate;
    frames = read_frames(files);
  }
  s.frame_rate = opt.frame_rate > 0 ? opt.frame_rate : rate;
  if (s.width == 0) {
    s.width = frames.front().width;
    s.height = frames.front().height;
  }
  out.events = emulate(frames, s);
  return out;
}

int emulate_command(EmulateOptions opt) {
  // Outputs are checked before the work, against every input file (a folder's frames too).
  std::vector<std::string> inputs = {opt.input};
  if (file_extension(opt.input) != ".y4m") {
    const SceneFiles files = find_scene(opt.input);
    inputs.insert(inputs.end(), files.frames.begin(), files.frames.end());
  }
  if (!opt.recon.empty()) check_image_path(opt.recon);
  const bool no_outputs = opt.queue.empty() && opt.out.empty() && opt.recon.empty();
  if (no_outputs) {
    opt.queue = "out/queue.txt";
    opt.out = "out/emulated.aedat";
  }
  if (!opt.out.empty()) {
    if (event_format_of(opt.out, "--out").format == EventFileFormat::Csv) {
      throw InputError(fmt::format("--out '{}': emulate writes no CSV; use --queue", opt.out));
    }
    writable_event_format(opt.out, "--out");
  }
  parse_aedat4_compression(opt.aedat4_compression);
  parse_raw_encoding(opt.raw_encoding);
  check_output_paths({{"--queue", opt.queue}, {"--out", opt.out}, {"--recon", opt.recon}}, inputs);

  const EmulatedRun run = emulate_frames(opt);
  const EmulatorSettings& s = run.settings;
  const std::vector<Image>& frames = run.frames;
  const std::vector<EmulatedEvent>& events = run.events;

  // The imager as one tile, so the AEDAT address is (y << xbits) | x and aesim can read it back.
  SensorConfig sensor;
  sensor.array.rows = sensor.array.tile_rows = s.height;
  sensor.array.cols = sensor.array.tile_cols = s.width;
  const AddressMap map(sensor.array);
  std::vector<AddressEvent> stream;
  for (const EmulatedEvent& e : events) {
    AddressEvent a = map.event_at({e.x, e.y});
    a.t = e.t;
    stream.push_back(a);
  }
  OutputFiles files;
  if (!opt.queue.empty()) {
    std::string text;
    for (const EmulatedEvent& e : events) fmt::format_to(std::back_inserter(text), "{} {}\n", e.x, e.y);
    files.open(opt.queue) << text;
  }
  if (!opt.out.empty()) {
    // The header records what describes these events: the array (one tile), the emulator's
    // settings and the span of time they cover, not a simulation's defaults.
    EventFileSpec spec;
    spec.array = sensor.array;
    for (const auto& [key, value] : sensor_metadata(sensor.to_json())) {
      if (key.rfind("array.", 0) == 0) spec.sensor[key] = value;
    }
    const double span = static_cast<double>(frames.size()) / s.frame_rate;
    spec.sensor["emulate.behaviour"] = opt.behaviour;
    spec.sensor["emulate.f_max"] = fmt::format("{}", s.f_max);
    spec.sensor["emulate.spread"] = opt.spread;
    spec.sensor["emulate.frames"] = fmt::format("{}", frames.size());
    spec.sensor["emulate.frame_rate"] = fmt::format("{}Hz", s.frame_rate);
    spec.sensor["emulate.duration"] = fmt::format("{}s", span);
    spec.notes.push_back(fmt::format("# aesim emulate: behaviour {}, f_max {} events/frame ({} spread), {} frames at {} Hz",
                                     opt.behaviour, s.f_max, opt.spread, frames.size(), s.frame_rate));
    spec.tick = 1e-6;
    spec.duration = span;
    spec.compression = parse_aedat4_compression(opt.aedat4_compression);
    spec.raw_encoding = parse_raw_encoding(opt.raw_encoding);
    std::unique_ptr<EventFileWriter> writer = open_event_writer(files, opt.out, spec);
    writer->events(stream.data(), stream.size());
    writer->finish();
  }
  if (!opt.recon.empty()) {
    const std::vector<AddressEvent> used =
        opt.events > 0 ? first_events(stream, static_cast<std::size_t>(opt.events)) : stream;
    write_image(files.open(opt.recon), opt.recon, reconstruct(used, s.width, s.height, ReconMode::Histogram));
  }
  files.commit();
  fmt::print(report_stream(), "aesim emulate: {} frames {}x{} -> {} events ({} behaviour, f_max {} per frame)\n", frames.size(),
             s.width, s.height, events.size(), opt.behaviour, s.f_max);
  std::string written;
  for (const std::string* p : {&opt.queue, &opt.out, &opt.recon}) {
    if (!p->empty()) written += (written.empty() ? "" : ", ") + *p;
  }
  fmt::print(report_stream(), "  wrote {}\n", written);
  return 0;
}

}  // namespace aesim
