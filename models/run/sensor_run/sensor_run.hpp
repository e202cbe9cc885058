#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/events/event_stream.hpp"
#include "aesim/events/run_facts.hpp"
#include "aesim/scene/image.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

// What a run is made of, as `aesim run` takes it (docs/reference.md section 4).
struct RunSpec {
  std::string sensor = "aloha";   // a preset's name (models/sensors) or a .toml file
  std::string scene;              // an image file or a frame folder; empty: scenes/letters/A.pgm
  std::vector<Image> frames;      // or the scene's frames in memory (full-scale fractions); then
                                  // `scene` is not read
  std::vector<Setting> settings;  // {"pixel.c_int", "50fF"}, ... applied in order (later wins)
  // Files, each written only when named, all or none (a run that fails leaves none); the format
  // of `out` follows its extension (docs/event_files.md).
  std::string out, csv, recon, summary, truth, vcd;
  std::string vcd_from = "0s", vcd_to;  // the VCD's window; vcd_to empty: the whole run
  std::string aedat_layout = "aesim";   // aesim | dvs128 | davis240c | davis346 (AEDAT 2.0 only)
  std::string aedat4_compression = "lz4";
  std::string raw_encoding = "evt2";  // evt2 | evt3 (Prophesee RAW only)
  // Besides the files, every delivered event goes to this stream as the run makes it (in time
  // order), and with `keep_truth` every firing's fate.
  EventStream* stream = nullptr;
  bool keep_truth = false;
};

// What a run did.
struct RunReport {
  explicit RunReport(ResolvedConfig resolved) : config(std::move(resolved)) {}
  ResolvedConfig config;     // the preset with the scene's and the spec's settings, resolved
  Fidelity fidelity{};       // the rung that ran (auto resolved)
  double tick = 0;           // the receivers' stamp step, s
  std::string scene;         // the scene as named, or the default scene's name
  bool default_scene = false;
  int scene_width = 0, scene_height = 0;  // as stored, before resampling to the array
  std::size_t scene_frames = 0;
  TileCounters totals;       // over all tiles
  RunFacts facts;
  nlohmann::json summary;    // the summary JSON (docs/reference.md section 5)
  std::vector<std::string> written;     // the files named in the spec, in its order
  std::vector<std::string> rtl_traces;  // and with a VCD of the RTL receiver, its internals per tile
  // What the caller should tell its user: one line each (the calibrated range left, ghosts no
  // event file could place, frames too short for the queue model, a fixed step coarser than a
  // pixel's period, firings a reader of the file would lose). The library prints nothing: the
  // program prints them, the Python module raises them as warnings.
  std::vector<std::string> warnings;
};

// Configures, chooses the rung once, checks every output before any work (a bad path costs no
// simulation), loads the scene's photocurrents, simulates with the files written as the run goes,
// then writes the summary, reconstruction and waveforms, and commits every file at once.
// Bad input throws InputError with a one-line message naming it; a refused output OutputError.
RunReport run_sensor(const RunSpec& spec);

}  // namespace aesim
