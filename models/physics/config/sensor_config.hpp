#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "aesim/limits/limits.hpp"
#include "aesim/pixel/transfer_curve.hpp"
#include "aesim/power/power_model.hpp"

namespace aesim {

class TomlValue;

enum class InitialState { Reset, Random };
enum class BusAccess { Aloha, Arbitrated, Ideal };
// Event, Cycle and Queue are the reference's rungs; PixelProcesses and FixedStep are the baselines a
// SystemC engineer would write first (one process per pixel with exact times, the same results
// as Event; every pixel integrated on a clock of period sim.step).
enum class Fidelity { Queue, Event, Cycle, Auto, PixelProcesses, FixedStep };
enum class ReceiverModel { Reference, Rtl };
enum class FullPolicy { Drop, Hold };

struct ResolvedConfig;

// The sections of a configuration, each the parameters of one part of the sensor or of the run, in
// SI units; field names are the keys of docs/reference.md section 3. The models take the sections they need.
struct PixelParams {
  double c_int = 100e-15;   // F, integration capacitance
  double dv_int = 1.0;      // V, swing at which the pixel fires
  double i_max = 1e-12;     // A, photocurrent at full-scale scene value 1
  double i_dark = 0.0;      // A
  double t_reset = 0.0;     // s, no integration after each firing
  double mismatch = 0.0;    // relative std of the per-pixel threshold charge
  bool shot_noise = false;  // Gamma-distributed integration times
  InitialState initial = InitialState::Reset;
  TransferCurve transfer;   // measured period against photocurrent (aesim calibrate); empty: eq. 2
  // The charge a pixel collects between firings (eq. 2's c_int * dv_int), before mismatch.
  double threshold_charge() const { return c_int * dv_int; }
  // The current the pixel integrates at scene value v: i_dark + i_max * v (docs/reference.md section 1), or
  // with a transfer table the current that fires with the table's period (transfer_curve.hpp).
  double integrating_current(double v) const { return integrating_current_at(i_max * v); }
  // The same for a photocurrent (A) rather than a scene value.
  double integrating_current_at(double photocurrent) const {
    if (transfer.empty()) return i_dark + photocurrent;
    return transfer.integrating_current(photocurrent, threshold_charge(), i_dark, t_reset);
  }
};

struct ArrayParams {
  int rows = 64, cols = 64, tile_rows = 32, tile_cols = 32;
};

struct BusParams {
  BusAccess access = BusAccess::Aloha;
  double t_event = 100e-9;  // s, tau: how long one event holds the bus
  bool contention_detect = true;
};

struct ReceiverParams {
  double clock = 50e6;  // Hz
  double tick = 1e-6;   // s, timestamp resolution
  int fifo_depth = 16;
  ReceiverModel model = ReceiverModel::Reference;  // cycle fidelity: SystemC reference or Verilated RTL
  FullPolicy full_policy = FullPolicy::Drop;       // a full FIFO drops the event, or holds Ack back
};

struct SimParams {
  double duration = 1.0;  // s
  std::uint64_t seed = 1;
  Fidelity fidelity = Fidelity::Auto;
  int threads = 1;  // event fidelity: tiles simulated in parallel on this many threads (0: all cores)
  double step = 1e-6;  // s, the clock of the fixed_step baseline
  // The most work a run may ask for, in fired events (or frame wake-ups or fixed steps of a
  // pixel): estimated before the run starts, refused beyond this (see run_budget.hpp).
  double max_events = 1e8;
};

struct LightParams {
  double lux = 0;               // > 0: pixel.i_max is the photocurrent of full-scale light at this illuminance
  double responsivity = 0.3;    // A/W of the photodiode
  double efficacy = 683;        // lm/W: 555 nm light (photopic peak)
  double pixel_area = 900e-12;  // m^2: a 30 um pixel
  double fill_factor = 0.3;
};

struct AnalysisParams {
  double window = 1.0;   // s: readout window for dynamic range and reconstruction PSNR
  int min_events = 2;    // a pixel "covered" fires at least this often within the window
};

struct SceneParams {
  double frame_rate = 25.0;  // Hz, for frame folders without their own scene.toml
  bool loop = false;         // after the last frame: repeat the sequence, or hold the last frame
};

// One configuration key as `aesim config keys` lists it.
struct KeyInfo {
  std::string key, unit, meaning;
};

// Every parameter of a run: one member per section ("pixel.c_int" is pixel.c_int).
struct SensorConfig {
  PixelParams pixel;
  ArrayParams array;
  BusParams bus;
  ReceiverParams receiver;
  SimParams sim;
  PowerParams power;  // models/physics/power/power_model.hpp
  LightParams light;
  AnalysisParams analysis;
  SceneParams scene;

  // Sets one key ("pixel.c_int") from text with SI units; throws InputError naming the key.
  void set(const std::string& key, const std::string& value);
  // Every key with its value, as the summary and the AEDAT header echo them.
  nlohmann::json to_json() const;
  // Physical and structural consistency; throws InputError naming the offending key.
  void validate() const;
  // The parameters a run uses: validated (InputError naming the key), then with light.lux set,
  // pixel.i_max derived from the illuminance.
  ResolvedConfig resolved() const;

  static const std::vector<std::string>& keys();
  // Every key with its unit (or the names it takes) and meaning, in key order.
  static std::vector<KeyInfo> key_table();
};

// A configuration ready to run: validated, its derived values filled in. Only
// SensorConfig::resolved() makes one, so whatever takes a ResolvedConfig cannot be handed a preset
// as typed, before its illuminance is turned into a photocurrent.
struct ResolvedConfig : SensorConfig {
 private:
  friend struct SensorConfig;
  explicit ResolvedConfig(const SensorConfig& config) : SensorConfig(config) {}
};

// The file a sensor name (a preset in the data folder) or path names.
std::string sensor_file(const std::string& name_or_file);
// Loads a preset: NAME (a file in the sensors folder) or a path to a .toml file. A file that says
// base = "NAME" or "FILE.toml" (a path from the file's own folder) is read over that preset, in
// turn read over its own base (up to 8 deep; a loop is refused); the keys a file without a base
// leaves out keep SensorConfig's own values.
SensorConfig load_sensor(const std::string& name_or_file);
// Sets keys from a TOML file: "[section] key = value" tables, or, when `section` is given, plain
// "key = value" lines within that section. Values are strings with units, numbers or booleans. A
// top-level base = "..." is load_sensor's and left alone here.
void apply_toml_file(SensorConfig& config, const std::string& path, const std::string& section);
// The same from the file's text; `path` names it in messages.
void apply_toml_text(SensorConfig& config, const std::string& text, const std::string& path,
                     const std::string& section);
// The same from the file's parsed document.
void apply_toml_document(SensorConfig& config, const TomlValue& doc, const std::string& path,
                         const std::string& section);
// The folder where named presets live.
std::string sensors_dir();

const char* to_string(InitialState v);
const char* to_string(BusAccess v);
const char* to_string(Fidelity v);
const char* to_string(ReceiverModel v);
const char* to_string(FullPolicy v);

}  // namespace aesim
