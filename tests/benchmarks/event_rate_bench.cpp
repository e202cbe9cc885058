// Fired events per wall second: the event fidelity on the aloha preset with a letter and on a
// QCIF (176x144) array; the cycle fidelity on the same letter with the reference receiver and
// with the Verilated RTL; and the cost per receiver clock cycle of each receiver with the clock
// never stopped. All side by side in one run, so the ratios hold on a noisy machine.
#include <fcntl.h>
#include <unistd.h>

#include <benchmark/benchmark.h>
#include <lz4frame.h>
#include <systemc>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>
#include <streambuf>

#include "ceiling_probe.hpp"
#include "merge_probe.hpp"
#include "Vaer_receiver_drop_stepped.h"
#include "aesim/config/sensor_config.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/output/space_ahead.hpp"
#include "aesim/pixel/integrate_fire.hpp"
#include "aesim/pixel/pixel_draws.hpp"
#include "aesim/random/gamma_draw.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

void run(benchmark::State& state, const SensorConfig& config, const Scene& scene) {
  const Photocurrents photocurrents(scene, config.pixel);
  double events = 0, edges = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(config.resolved(), photocurrents);
    events += static_cast<double>(r.log.totals().fired);
    edges += static_cast<double>(r.facts.receiver_clock_edges);
    benchmark::DoNotOptimize(r.log.events().data());
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
  if (config.sim.fidelity == Fidelity::Cycle) {
    // Cycles of every tile's receiver clock covered by the run (the clock stops while a bus is
    // idle, so far fewer edges are simulated: edges_per_s).
    const double tiles = (config.array.rows / config.array.tile_rows) * (config.array.cols / config.array.tile_cols);
    const double covered = static_cast<double>(state.iterations()) * config.sim.duration * config.receiver.clock * tiles;
    state.counters["clock_cycles_per_s"] = benchmark::Counter(covered, benchmark::Counter::kIsRate);
    state.counters["edges_per_s"] = benchmark::Counter(edges, benchmark::Counter::kIsRate);
  }
}

Scene scene_for(const SensorConfig& c, const char* relative) {
  return load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/" + relative), c.array, c.scene);
}

void BM_EventLetterA(benchmark::State& state) {
  SensorConfig c = load_sensor("aloha");
  c.sim.duration = 10.0;
  c.sim.fidelity = Fidelity::Event;
  run(state, c, scene_for(c, "scenes/letters/A.pgm"));
}

void BM_CycleLetterA(benchmark::State& state) {
  SensorConfig c = load_sensor("aloha");
  c.sim.duration = 10.0;
  c.sim.fidelity = Fidelity::Cycle;
  run(state, c, scene_for(c, "scenes/letters/A.pgm"));
}

void BM_CycleLetterA_Rtl(benchmark::State& state) {
  SensorConfig c = load_sensor("aloha");
  c.sim.duration = 10.0;
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.model = ReceiverModel::Rtl;
  run(state, c, scene_for(c, "scenes/letters/A.pgm"));
}

// The least work the RTL in the loop must do: the Verilated receiver (the plain C++ model the cycle
// rung steps) clocked in a bare loop, rising and falling edge each an eval(), inputs idle.
void BM_RtlEvalProbe(benchmark::State& state) {
  Vaer_receiver_drop_stepped rtl("rtl");
  rtl.prescale_i = 50;
  rtl.fifo_limit_i = 16;
  rtl.evt_ready_i = 1;
  rtl.rst_ni = 0;
  rtl.eval();
  rtl.rst_ni = 1;
  constexpr int kCycles = 1000000;
  for (auto _ : state) {
    for (int i = 0; i < kCycles; ++i) {
      rtl.clk_i = 1;
      rtl.eval();
      rtl.clk_i = 0;
      rtl.eval();
    }
  }
  rtl.final();
  state.counters["edges_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kCycles, benchmark::Counter::kIsRate);
}

// A receiver with its clock running throughout (no gating): what each costs per clock cycle.
void BM_CycleFreeRunningClock(benchmark::State& state, ReceiverModel model) {
  SensorConfig c = load_sensor("aloha");
  c.sim.duration = 0.05;
  c.sim.fidelity = Fidelity::Cycle;
  c.receiver.model = model;
  const Scene scene = scene_for(c, "scenes/letters/A.pgm");
  const Photocurrents photocurrents(scene, c.pixel);
  SimulationRequest request;
  request.cycle.free_running_clock = true;
  double edges = 0;
  for (auto _ : state) {
    const SimulationResult r = simulate(c.resolved(), photocurrents, request);
    edges += static_cast<double>(r.facts.receiver_clock_edges);
  }
  state.counters["edges_per_s"] = benchmark::Counter(edges, benchmark::Counter::kIsRate);
}

// A bright 176x144 scene (uniform full light, 10 Hz per pixel, ~253,000 events/s, 20 s): the
// event rung counting only, writing AEDAT (to a sink that takes the bytes, so the packing is
// paid for but no disk), and counting on two threads; the one-process-per-pixel baseline; and the
// ceiling probe on the same pixels. scripts/bench prints their ratios.
SensorConfig qcif_bright(Fidelity fidelity, double duration, int threads) {
  SensorConfig c = load_sensor("aloha");
  c.array.rows = 144;
  c.array.cols = 176;
  c.sim.duration = duration;
  c.sim.fidelity = fidelity;
  c.sim.threads = threads;
  return c;
}

// Takes every byte and keeps none.
class ByteSink : public std::streambuf {
 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
  int_type overflow(int_type c) override { return traits_type::not_eof(c); }
};

void BM_QcifBright(benchmark::State& state, int threads, bool aedat, bool shot_noise) {
  SensorConfig c = qcif_bright(Fidelity::Event, 20.0, threads);
  c.pixel.shot_noise = shot_noise;
  const Scene scene = scene_for(c, "scenes/uniform.pgm");
  const Photocurrents photocurrents(scene, c.pixel);
  const ResolvedConfig config = c.resolved();
  const AddressMap map(config.array);
  double events = 0;
  for (auto _ : state) {
    ByteSink bytes;
    std::ostream out(&bytes);
    AedatWriter writer(out, aedat_header(map, {}), map, config.receiver.tick);
    SimulationRequest request;
    request.keep_events = aedat;
    request.stream = &writer;
    const SimulationResult r = simulate(config, photocurrents, request);
    events += static_cast<double>(r.log.totals().fired);
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// Runs `config` with its events written to `path` (a file of the format its extension names, under
// the system's temporary folder, as `aesim run --out` writes it, never committed: the page cache
// takes it, the disk is not waited for), set-up included; the file is removed between rounds,
// outside the time measured (removing a previous output is not part of writing one).
void run_written(benchmark::State& state, const ResolvedConfig& config, const Photocurrents& photocurrents,
                 const std::string& name, Aedat4Compression compression) {
  EventFileSpec spec;
  spec.array = config.array;
  spec.tick = config.receiver.tick;
  spec.duration = config.sim.duration;
  spec.compression = compression;
  const std::string path = (std::filesystem::temp_directory_path() / ("aesim_bench_" + name)).string();
  double events = 0;
  for (auto _ : state) {
    auto files = std::make_unique<OutputFiles>();
    auto writer = open_event_writer(*files, path, spec);
    SimulationRequest request;
    request.keep_events = true;
    request.stream = writer.get();
    events += static_cast<double>(simulate(config, photocurrents, request).log.totals().fired);
    writer->finish();
    state.PauseTiming();
    writer.reset();
    files.reset();
    state.ResumeTiming();
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// The bright QCIF with its events written to a file of each format.
void BM_QcifWritten(benchmark::State& state, const char* name, int threads) {
  const SensorConfig c = qcif_bright(Fidelity::Event, 20.0, threads);
  const Photocurrents photocurrents(scene_for(c, "scenes/uniform.pgm"), c.pixel);
  run_written(state, c.resolved(), photocurrents, name,
              std::string(name) == "plain.aedat4" ? Aedat4Compression::None : Aedat4Compression::Lz4);
}

// A large array (N x N pixels in 32x32 tiles, uniform full light, 10 events a pixel a second) with
// its events written to an AEDAT 2.0 file for a number of milliseconds: against the QCIF's AEDAT,
// how the rate holds as the tiles grow in number. A run of 1 s and one of 2 s side by side tell
// the second second's rate from the set-up's cost (scripts/bench).
void BM_ArrayWritten(benchmark::State& state) {
  SensorConfig c = qcif_bright(Fidelity::Event, static_cast<double>(state.range(1)) * 1e-3, 1);
  c.array.rows = c.array.cols = static_cast<int>(state.range(0));
  const Photocurrents photocurrents(scene_for(c, "scenes/uniform.pgm"), c.pixel);
  run_written(state, c.resolved(), photocurrents, "large.aedat", Aedat4Compression::Lz4);
}

// LZ4 alone on the packets an .aedat4 holds: 4096 events of DV's 16-byte Event (stamp, x, y,
// polarity) from the bright QCIF's firing pattern, each packet one LZ4 frame, as the writer makes
// them. The least work compressed AEDAT 4.0 must do.
void BM_Lz4Probe(benchmark::State& state) {
  const SensorConfig c = qcif_bright(Fidelity::Event, 2.0, 1);
  const Photocurrents photocurrents(scene_for(c, "scenes/uniform.pgm"), c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  struct DvEvent {
    std::int64_t t;
    std::int16_t x, y;
    std::uint8_t on, pad[3];
  };
  static_assert(sizeof(DvEvent) == 16, "DV's Event is 16 bytes");
  std::vector<DvEvent> packed;
  for (const AddressEvent& e : r.log.events()) {
    packed.push_back({static_cast<std::int64_t>(std::llround(e.t * 1e6)), static_cast<std::int16_t>(e.x),
                      static_cast<std::int16_t>(e.y), 1, {0, 0, 0}});
  }
  constexpr std::size_t kPacket = 4096;
  LZ4F_preferences_t prefs{};
  std::vector<char> out(LZ4F_compressFrameBound(kPacket * sizeof(DvEvent), &prefs));
  double events = 0;
  for (auto _ : state) {
    for (std::size_t at = 0; at < packed.size(); at += kPacket) {
      const std::size_t n = std::min(kPacket, packed.size() - at);
      prefs.frameInfo.contentSize = n * sizeof(DvEvent);
      benchmark::DoNotOptimize(
          LZ4F_compressFrame(out.data(), out.size(), packed.data() + at, n * sizeof(DvEvent), &prefs));
    }
    events += static_cast<double>(packed.size());
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// The system's part of writing a file, as the .npy writer hands it over: the 66 MB the bright
// QCIF's 20 s make as .npy, a megabyte a write, to a new file, with disk space reserved ahead of
// the writes (SpaceAhead, as every event file does) or without. Counted in the same events as the
// QCIF benchmarks, so that the rate sets a ceiling beside theirs.
void BM_FileWriteProbe(benchmark::State& state) {
  const bool reserve = state.range(0) != 0;
  constexpr std::size_t kEvents = 5'080'000, kRecordBytes = 13, kWrite = std::size_t(1) << 20;
  const std::string path = (std::filesystem::temp_directory_path() / "aesim_bench_write_probe").string();
  const std::vector<char> block(kWrite, '\x5a');
  double events = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove(path);
    state.ResumeTiming();
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      state.SkipWithError("cannot make the probe's file");
      break;
    }
    SpaceAhead space;
    for (std::uint64_t at = 0; at < kEvents * kRecordBytes; at += kWrite) {
      const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(kWrite, kEvents * kRecordBytes - at));
      if (reserve) space.before_writing_to(fd, at + n);
      if (::write(fd, block.data(), n) != static_cast<ssize_t>(n)) state.SkipWithError("a write failed");
    }
    space.release(fd);
    ::close(fd);
    events += static_cast<double>(kEvents);
  }
  std::filesystem::remove(path);
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// The merge of the bright QCIF's tiles' streams (its 5 M delivered events in 20 windows, as the
// event log hands them over) by the run's own EventMerger into a stream that keeps nothing, and
// the probe of the least work a merge must do (merge_probe.hpp) on the same windows.
const RecordedWindows& qcif_windows() {
  static const RecordedWindows recorded = [] {
    const SensorConfig c = qcif_bright(Fidelity::Event, 20.0, 1);
    return record_windows(c.resolved(), Photocurrents(scene_for(c, "scenes/uniform.pgm"), c.pixel), 20);
  }();
  return recorded;
}

class NullStream : public EventStream {
 public:
  void events(const AddressEvent* first, std::size_t count) override { benchmark::DoNotOptimize(first + count); }
};

void BM_QcifMerge(benchmark::State& state) {
  const RecordedWindows& recorded = qcif_windows();
  double events = 0;
  NullStream null;
  // One merger throughout, as in a run (its buffers reused); each pass over the windows ends with
  // nothing held, so the next starts afresh.
  EventMerger merger(recorded.windows.front().events.size(), null);
  std::vector<TileRecords> windows;
  for (auto _ : state) {
    state.PauseTiming();
    windows = recorded.windows;
    state.ResumeTiming();
    for (std::size_t i = 0; i < windows.size(); ++i) merger.merge(windows[i], recorded.before[i]);
    events += static_cast<double>(recorded.events);
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

void BM_MergeProbe(benchmark::State& state) {
  const RecordedWindows& recorded = qcif_windows();
  double events = 0;
  for (auto _ : state) {
    const std::uint64_t made = merge_probe(recorded);
    if (made != recorded.events) state.SkipWithError("the merge probe lost records");
    events += static_cast<double>(made);
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// The QCIF array at i_max 100 pA on the moving disc (the disc at about 1 kHz a pixel, the field at
// about 20 Hz): its 24 frames shown at 100 Hz and looped, so the light changes every 10 ms for the
// whole 2 s; and, as the still scene of the same light, its first frame alone. Summary only.
void BM_QcifMoving(benchmark::State& state, bool moving, int threads) {
  SensorConfig c = qcif_bright(Fidelity::Event, 2.0, threads);
  c.pixel.i_max = 100e-12;
  Scene scene = scene_for(c, "scenes/moving_disc");
  if (moving) {
    scene.frame_period = 0.01;
    scene.loop = true;
  } else {
    scene.frames.resize(1);
  }
  const Photocurrents photocurrents(scene, c.pixel);
  const ResolvedConfig config = c.resolved();
  double events = 0;
  SimulationRequest summary_only;
  summary_only.keep_events = false;
  for (auto _ : state) {
    events += static_cast<double>(simulate(config, photocurrents, summary_only).log.totals().fired);
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

void BM_QcifPixelProcesses(benchmark::State& state) {
  SensorConfig c = qcif_bright(Fidelity::PixelProcesses, 2.0, 1);
  run(state, c, scene_for(c, "scenes/uniform.pgm"));
}

// The ceiling probe on the bright QCIF's pixels: each period constant, or with `shot_noise` each
// drawn as the model draws it (the pixel's threshold over its current, its electron count from
// the gamma law by the model's own sampler, plus the reset).
void BM_QcifCeilingProbe(benchmark::State& state, bool shot_noise) {
  const SensorConfig c = qcif_bright(Fidelity::Event, 20.0, 1);
  const Photocurrents photocurrents(scene_for(c, "scenes/uniform.pgm"), c.pixel);
  std::vector<double> periods, phases, seconds_per_electron;
  std::vector<GammaDraw> electrons;
  std::vector<SplitMix64> streams;
  for (std::size_t i = 0; i < std::size_t(144) * 176; ++i) {
    const double current = photocurrents.current(0, i);
    const double threshold = pixel_threshold(c.pixel, c.sim.seed, i);
    const double period = threshold / current + c.pixel.t_reset;
    periods.push_back(period);
    phases.push_back((1 - initial_fraction(c.pixel, c.sim.seed, i)) * period);
    electrons.emplace_back(threshold / kElectronCharge);
    seconds_per_electron.push_back(kElectronCharge / current);
    streams.push_back(shot_noise_stream(c.sim.seed, i));
  }
  std::vector<double> sorted = periods;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  const double t_reset = c.pixel.t_reset;
  double events = 0;
  for (auto _ : state) {
    std::vector<double> t = phases;
    if (shot_noise) {
      events += static_cast<double>(ceiling_probe(t, median, 0.0, c.sim.duration, [&](std::uint32_t i) {
        return t_reset + seconds_per_electron[i] * electrons[i](streams[i]);
      }));
    } else {
      events += static_cast<double>(
          ceiling_probe(t, median, 0.0, c.sim.duration, [&](std::uint32_t i) { return periods[i]; }));
    }
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// The least work the moving disc must do (BM_QcifMoving's scene, 200 frame changes in 2 s): the
// ceiling probe through each frame on that frame's periods, and at each change every pixel
// re-timed, its remaining charge now crossed at the new rate (one multiply a pixel), and put back
// in the calendar.
void BM_FrameChangeProbe(benchmark::State& state) {
  SensorConfig c = qcif_bright(Fidelity::Event, 2.0, 1);
  c.pixel.i_max = 100e-12;
  Scene scene = scene_for(c, "scenes/moving_disc");
  scene.frame_period = 0.01;
  scene.loop = true;
  const Photocurrents photocurrents(scene, c.pixel);
  const std::size_t pixels = std::size_t(144) * 176, frames = photocurrents.frames();
  std::vector<std::vector<double>> periods(frames, std::vector<double>(pixels));
  std::vector<double> phases(pixels), all;
  for (std::size_t i = 0; i < pixels; ++i) {
    const double threshold = pixel_threshold(c.pixel, c.sim.seed, i);
    for (std::size_t k = 0; k < frames; ++k) {
      periods[k][i] = threshold / photocurrents.current(k, i) + c.pixel.t_reset;
      all.push_back(periods[k][i]);
    }
    phases[i] = (1 - initial_fraction(c.pixel, c.sim.seed, i)) * periods[0][i];
  }
  std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2), all.end());
  const double median = all[all.size() / 2];
  const auto changes = static_cast<std::size_t>(std::llround(c.sim.duration / scene.frame_period));
  double events = 0;
  for (auto _ : state) {
    std::vector<double> t = phases;
    for (std::size_t s = 0; s < changes; ++s) {
      const std::vector<double>& now = periods[s % frames];
      const double begin = static_cast<double>(s) * scene.frame_period, end = begin + scene.frame_period;
      events += static_cast<double>(ceiling_probe(t, median, begin, end, [&](std::uint32_t i) { return now[i]; }));
      const std::vector<double>& next = periods[(s + 1) % frames];
      for (std::size_t i = 0; i < pixels; ++i) t[i] = end + (t[i] - end) * (next[i] / now[i]);
    }
  }
  state.counters["events_per_s"] = benchmark::Counter(events, benchmark::Counter::kIsRate);
}

// One lit pixel (1 MHz, 1 s: a million firings) in an N x N array of 32x32 tiles, the rest dark:
// the cost must follow the events, not the pixels.
void BM_OneLitPixel(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  SensorConfig c = load_sensor("aloha");
  c.array.rows = c.array.cols = n;
  c.pixel.i_dark = 0;
  c.pixel.i_max = 100e-9;
  c.sim.duration = 1.0;
  c.sim.fidelity = Fidelity::Event;
  Scene scene;
  Image img;
  img.width = img.height = n;
  img.pixels.assign(static_cast<std::size_t>(n) * n, 0.0);
  img.pixels[static_cast<std::size_t>(n / 2) * n + n / 2] = 1.0;
  scene.frames.push_back(img);
  scene.frame_period = 1.0;
  run(state, c, scene);
}

BENCHMARK(BM_OneLitPixel)->Arg(32)->Arg(1024)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_EventLetterA)->Unit(benchmark::kMillisecond)->MinTime(2.0);
// The cycle rung and its eval() probe repeat six times, interleaved at random with the others as
// the QCIF benchmarks are, so that the ratios scripts/bench prints (of medians, per CPU second of
// the one thread they run on) compare runs spread over the same stretch of time.
void cycle_rung(benchmark::internal::Benchmark* b) {
  b->Unit(benchmark::kMillisecond)->MinTime(1.0)->Repetitions(6)->DisplayAggregatesOnly(true);
}
BENCHMARK(BM_CycleLetterA)->Apply(cycle_rung);
BENCHMARK(BM_CycleLetterA_Rtl)->Apply(cycle_rung);
BENCHMARK(BM_RtlEvalProbe)->Apply(cycle_rung);
BENCHMARK_CAPTURE(BM_CycleFreeRunningClock, Reference, ReceiverModel::Reference)->Apply(cycle_rung);
BENCHMARK_CAPTURE(BM_CycleFreeRunningClock, Rtl, ReceiverModel::Rtl)->Apply(cycle_rung);
// Rates per wall second (UseRealTime): writing AEDAT and the second tile thread work beside the
// benchmark's own thread, whose CPU time alone would flatter them. Six repetitions each, which
// scripts/bench interleaves at random with the others', so that the ratios it prints (of
// medians) compare runs spread over the same stretch of a noisy machine's time.
void qcif(benchmark::internal::Benchmark* b) {
  b->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime()->Repetitions(6)->DisplayAggregatesOnly(true);
}
BENCHMARK_CAPTURE(BM_QcifCeilingProbe, still, false)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifCeilingProbe, shot_noise, true)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifBright, summary_1_thread, 1, false, false)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifBright, shot_noise_1_thread, 1, false, true)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifMoving, still, false, 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifMoving, moving, true, 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifMoving, moving_2_threads, true, 2)->Apply(qcif);
BENCHMARK(BM_FrameChangeProbe)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifBright, aedat_1_thread, 1, true, false)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, aedat, "e.aedat", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, aedat4, "e.aedat4", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, aedat4_plain, "plain.aedat4", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, npy, "e.npy", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, h5, "e.h5", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, raw, "e.raw", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, dat, "e.dat", 1)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifWritten, aedat_2_threads, "e2.aedat", 2)->Apply(qcif);
BENCHMARK(BM_Lz4Probe)->Apply(qcif);
BENCHMARK(BM_FileWriteProbe)->Arg(0)->Arg(1)->Apply(qcif);
BENCHMARK(BM_QcifMerge)->Apply(qcif);
BENCHMARK(BM_MergeProbe)->Apply(qcif);
BENCHMARK_CAPTURE(BM_QcifBright, summary_2_threads, 2, false, false)->Apply(qcif);
BENCHMARK(BM_ArrayWritten)
    ->Args({1024, 1000})
    ->Args({2048, 1000})
    ->Args({2048, 2000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(3);
BENCHMARK(BM_QcifPixelProcesses)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace aesim
