#include "aesim/config/sensor_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "aesim/array/address_map.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/files/toml_file.hpp"
#include "aesim/text/ascii_case.hpp"
#include "aesim/text/nearest_name.hpp"
#include "aesim/power/power_model.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

struct KeySpec {
  std::function<void(SensorConfig&, const std::string&)> set;
  std::function<nlohmann::json(const SensorConfig&)> get;
  std::string unit;     // SI unit, or the names an enumeration takes ("aloha|arbitrated|ideal")
  std::string meaning;  // one line, for `aesim config keys` and docs/configuration_keys.md
};

using Json = nlohmann::json;

bool parse_bool(const std::string& text, const std::string& key) {
  const std::string t = ascii_lower(text);
  if (t == "true" || t == "1" || t == "yes" || t == "on") return true;
  if (t == "false" || t == "0" || t == "no" || t == "off") return false;
  throw InputError(fmt::format("{}: expected true or false (got '{}')", key, text));
}

long long parse_integer(const std::string& text, const std::string& key) {
  const double v = parse_si(text, "", key);
  if (v != std::floor(v) || std::fabs(v) > 9.0e15) {
    throw InputError(fmt::format("{}: expected a whole number (got '{}')", key, text));
  }
  return static_cast<long long>(v);
}

template <typename Enum>
Enum parse_enum(const std::string& text, const std::string& key,
                const std::vector<std::pair<const char*, Enum>>& names) {
  const std::string t = ascii_lower(text);
  std::string allowed;
  for (const auto& [name, value] : names) {
    if (t == name) return value;
    allowed += allowed.empty() ? name : std::string("|") + name;
  }
  throw InputError(fmt::format("{}: expected one of {} (got '{}')", key, allowed, text));
}

const std::vector<std::pair<const char*, InitialState>> kInitial = {
    {"reset", InitialState::Reset}, {"random", InitialState::Random}};
const std::vector<std::pair<const char*, BusAccess>> kAccess = {
    {"aloha", BusAccess::Aloha}, {"arbitrated", BusAccess::Arbitrated}, {"ideal", BusAccess::Ideal}};
const std::vector<std::pair<const char*, ReceiverModel>> kReceiverModel = {{"reference", ReceiverModel::Reference},
                                                                          {"rtl", ReceiverModel::Rtl}};
const std::vector<std::pair<const char*, FullPolicy>> kFullPolicy = {{"drop", FullPolicy::Drop},
                                                                    {"hold", FullPolicy::Hold}};
const std::vector<std::pair<const char*, Fidelity>> kFidelity = {{"queue", Fidelity::Queue},
                                                                 {"event", Fidelity::Event},
                                                                 {"cycle", Fidelity::Cycle},
                                                                 {"auto", Fidelity::Auto},
                                                                 {"pixel_processes", Fidelity::PixelProcesses},
                                                                 {"fixed_step", Fidelity::FixedStep}};

const std::map<std::string, KeySpec>& registry() {
  static const std::map<std::string, KeySpec> table = [] {
    std::map<std::string, KeySpec> t;
    auto real = [&t](const std::string& key, const char* unit, auto field, const char* meaning) {
      t[key] = {[key, unit, field](SensorConfig& c, const std::string& v) {
                  field(c) = parse_si(v, unit, key);
                },
                [field](const SensorConfig& c) {
                  return Json(field(c));
                },
                unit, meaning};
    };
    auto integer = [&t](const std::string& key, auto field, const char* meaning) {
      t[key] = {[key, field](SensorConfig& c, const std::string& v) {
                  const long long n = parse_integer(v, key);
                  if (n < 0 || n > (1LL << 30)) {
                    throw InputError(fmt::format("{}: {} is out of range", key, v));
                  }
                  field(c) = static_cast<int>(n);
                },
                [field](const SensorConfig& c) {
                  return Json(field(c));
                },
                "", meaning};
    };
    auto boolean = [&t](const std::string& key, auto field, const char* meaning) {
      t[key] = {[key, field](SensorConfig& c, const std::string& v) { field(c) = parse_bool(v, key); },
                [field](const SensorConfig& c) {
                  return Json(field(c));
                },
                "true|false", meaning};
    };
    auto enumerated = [&t](const std::string& key, auto field, const auto& names, const char* meaning) {
      std::string allowed;
      for (const auto& entry : names) allowed += (allowed.empty() ? "" : "|") + std::string(entry.first);
      t[key] = {[key, field, &names](SensorConfig& c, const std::string& v) {
                  field(c) = parse_enum(v, key, names);
                },
                [field](const SensorConfig& c) {
                  return Json(to_string(field(c)));
                },
                allowed, meaning};
    };
    real("pixel.c_int", "F", [](auto& c) -> auto& { return c.pixel.c_int; },
         "integration capacitance (eq. 2: a firing every c_int * dv_int / I_ph)");
    real("pixel.dv_int", "V", [](auto& c) -> auto& { return c.pixel.dv_int; },
         "voltage swing from reset to the comparator's threshold");
    real("pixel.i_max", "A", [](auto& c) -> auto& { return c.pixel.i_max; },
         "photocurrent of full-scale light (a scene value of 1); set from light.lux when that is set");
    real("pixel.i_dark", "A", [](auto& c) -> auto& { return c.pixel.i_dark; },
         "dark current, added to every pixel's photocurrent");
    real("pixel.t_reset", "s", [](auto& c) -> auto& { return c.pixel.t_reset; },
         "reset time after each firing, during which the pixel does not integrate");
    real("pixel.mismatch", "", [](auto& c) -> auto& { return c.pixel.mismatch; },
         "relative standard deviation of each pixel's threshold charge (fixed-pattern noise)");
    boolean("pixel.shot_noise", [](auto& c) -> auto& { return c.pixel.shot_noise; },
            "Poisson photon shot noise on each integration");
    enumerated("pixel.initial", [](auto& c) -> auto& { return c.pixel.initial; }, kInitial,
               "charge at time 0: reset (all empty, a global reset) or random (a sensor that has been running)");
    t["pixel.transfer"] = {[](SensorConfig& c, const std::string& v) {
                             c.pixel.transfer = transfer_from_text(v, "pixel.transfer");
                           },
                           [](const SensorConfig& c) {
                             if (c.pixel.transfer.empty()) return Json(nullptr);
                             Json table{{"current", c.pixel.transfer.current}, {"period", c.pixel.transfer.period}};
                             if (c.pixel.transfer.charge > 0) table["charge"] = c.pixel.transfer.charge;
                             if (c.pixel.transfer.t_reset >= 0) table["t_reset"] = c.pixel.transfer.t_reset;
                             if (c.pixel.transfer.silent_below > 0) table["silent_below"] = c.pixel.transfer.silent_below;
                             if (std::isfinite(c.pixel.transfer.silent_above)) {
                               table["silent_above"] = c.pixel.transfer.silent_above;
                             }
                             return table;
                           },
                           "table",
                           "measured firing period against photocurrent (aesim calibrate), or none for eq. 2"};
    integer("array.rows", [](auto& c) -> auto& { return c.array.rows; }, "pixel rows of the whole array");
    integer("array.cols", [](auto& c) -> auto& { return c.array.cols; }, "pixel columns of the whole array");
    integer("array.tile_rows", [](auto& c) -> auto& { return c.array.tile_rows; },
            "pixel rows of one tile (a tile has its own bus and receiver)");
    integer("array.tile_cols", [](auto& c) -> auto& { return c.array.tile_cols; }, "pixel columns of one tile");
    enumerated("bus.access", [](auto& c) -> auto& { return c.bus.access; }, kAccess,
               "aloha (no arbiter: overlapping requests collide), arbitrated (queued) or ideal (no loss)");
    real("bus.t_event", "s", [](auto& c) -> auto& { return c.bus.t_event; },
         "duration of one bus transaction (tau) at the event fidelity");
    boolean("bus.contention_detect", [](auto& c) -> auto& { return c.bus.contention_detect; },
            "the bus flags a collision so the receiver can drop the corrupt address");
    real("receiver.clock", "Hz", [](auto& c) -> auto& { return c.receiver.clock; },
         "receiver clock (cycle fidelity: the handshake's timing)");
    real("receiver.tick", "s", [](auto& c) -> auto& { return c.receiver.tick; }, "timestamp resolution");
    integer("receiver.fifo_depth", [](auto& c) -> auto& { return c.receiver.fifo_depth; },
            "receiver FIFO words (cycle fidelity)");
    enumerated("receiver.model", [](auto& c) -> auto& { return c.receiver.model; }, kReceiverModel,
               "cycle fidelity's receiver: the C++ reference or the Verilog RTL through Verilator");
    enumerated("receiver.full_policy", [](auto& c) -> auto& { return c.receiver.full_policy; }, kFullPolicy,
               "a full FIFO drops the new address, or holds Ack until a word frees");
    real("sim.duration", "s", [](auto& c) -> auto& { return c.sim.duration; }, "simulated time");
    t["sim.seed"] = {[](SensorConfig& c, const std::string& v) {
                       const long long n = parse_integer(v, "sim.seed");
                       if (n < 0) throw InputError("sim.seed: must not be negative (got '" + v + "')");
                       c.sim.seed = static_cast<std::uint64_t>(n);
                     },
                     [](const SensorConfig& c) { return Json(c.sim.seed); }, "",
                     "seed of every random stream (mismatch, initial charge, shot noise)"};
    enumerated("sim.fidelity", [](auto& c) -> auto& { return c.sim.fidelity; }, kFidelity,
               "the rung that simulates the run; auto chooses the fastest exact one");
    integer("sim.threads", [](auto& c) -> auto& { return c.sim.threads; },
            "event fidelity: tiles simulated in parallel on this many threads (0: all cores); a run that writes "
            "events merges them on one more thread with 1 (which also makes half the tiles' schedules before the "
            "first window, on arrays of 8192 pixels or more), and among these threads with more");
    real("sim.step", "s", [](auto& c) -> auto& { return c.sim.step; }, "time step of the fixed_step baseline");
    real("sim.max_events", "", [](auto& c) -> auto& { return c.sim.max_events; },
         "the most work a run may ask for, in events, estimated before it starts");
    real("power.vdd", "V", [](auto& c) -> auto& { return c.power.vdd; }, "supply voltage of the power estimate");
    real("power.e_pixel_event", "J", [](auto& c) -> auto& { return c.power.e_pixel_event; },
         "energy of a firing beyond recharging c_int (comparator, logic)");
    real("power.c_bus_line", "F", [](auto& c) -> auto& { return c.power.c_bus_line; },
         "capacitance of one bus line, charged per transaction for each 1 bit, Req and Ack");
    real("power.e_receiver_event", "J", [](auto& c) -> auto& { return c.power.e_receiver_event; },
         "receiver energy per bus transaction");
    real("power.p_static_pixel", "W", [](auto& c) -> auto& { return c.power.p_static_pixel; },
         "static power of one pixel (comparator and amplifier bias)");
    real("light.lux", "lx", [](auto& c) -> auto& { return c.light.lux; },
         "illuminance of full-scale light; above 0 it sets pixel.i_max");
    real("light.responsivity", "A/W", [](auto& c) -> auto& { return c.light.responsivity; },
         "photodiode responsivity");
    real("light.efficacy", "lm/W", [](auto& c) -> auto& { return c.light.efficacy; },
         "luminous efficacy of the light (683 lm/W: 555 nm)");
    real("light.pixel_area", "m2", [](auto& c) -> auto& { return c.light.pixel_area; }, "area of one pixel");
    real("light.fill_factor", "", [](auto& c) -> auto& { return c.light.fill_factor; },
         "fraction of the pixel's area that collects light");
    real("analysis.window", "s", [](auto& c) -> auto& { return c.analysis.window; },
         "readout window of the dynamic range and the reconstruction's PSNR");
    integer("analysis.min_events", [](auto& c) -> auto& { return c.analysis.min_events; },
            "a pixel counts as covered when it fires at least this often within the window");
    real("scene.frame_rate", "Hz", [](auto& c) -> auto& { return c.scene.frame_rate; },
         "frames per second of a frame folder (its scene.toml may set it) or a Y4M video (its header sets it); --set wins");
    boolean("scene.loop", [](auto& c) -> auto& { return c.scene.loop; },
            "after the last frame, repeat the sequence (or hold the last frame)");
    return t;
  }();
  return table;
}

void require(bool ok, const char* key, const std::string& why) {
  if (!ok) throw InputError(fmt::format("{}: {}", key, why));
}

}  // namespace

const char* to_string(InitialState v) { return v == InitialState::Reset ? "reset" : "random"; }
const char* to_string(BusAccess v) {
  switch (v) {
    case BusAccess::Aloha: return "aloha";
    case BusAccess::Arbitrated: return "arbitrated";
    case BusAccess::Ideal: return "ideal";
  }
  return "?";
}
const char* to_string(ReceiverModel v) { return v == ReceiverModel::Reference ? "reference" : "rtl"; }
const char* to_string(FullPolicy v) { return v == FullPolicy::Drop ? "drop" : "hold"; }
const char* to_string(Fidelity v) {
  switch (v) {
    case Fidelity::Queue: return "queue";
    case Fidelity::Event: return "event";
    case Fidelity::Cycle: return "cycle";
    case Fidelity::Auto: return "auto";
    case Fidelity::PixelProcesses: return "pixel_processes";
    case Fidelity::FixedStep: return "fixed_step";
  }
  return "?";
}

void SensorConfig::set(const std::string& key, const std::string& value) {
  const auto& table = registry();
  const auto it = table.find(key);
  if (it == table.end()) throw InputError(fmt::format("unknown key '{}'{}", key, did_you_mean(key, keys())));
  it->second.set(*this, value);
}

nlohmann::json SensorConfig::to_json() const {
  Json out = Json::object();
  for (const auto& [key, spec] : registry()) {
    const auto dot = key.find('.');
    out[key.substr(0, dot)][key.substr(dot + 1)] = spec.get(*this);
  }
  return out;
}

std::vector<KeyInfo> SensorConfig::key_table() {
  std::vector<KeyInfo> out;
  for (const auto& [key, spec] : registry()) out.push_back({key, spec.unit, spec.meaning});
  return out;
}

const std::vector<std::string>& SensorConfig::keys() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& entry : registry()) v.push_back(entry.first);
    return v;
  }();
  return names;
}

void SensorConfig::validate() const {
  require(pixel.c_int > 0, "pixel.c_int", "capacitance must be positive");
  require(pixel.dv_int > 0, "pixel.dv_int", "swing must be positive");
  require(pixel.i_max >= 0, "pixel.i_max", "photocurrent must not be negative");
  require(pixel.i_dark >= 0, "pixel.i_dark", "dark current must not be negative");
  require(pixel.t_reset >= 0, "pixel.t_reset", "reset time must not be negative");
  require(pixel.mismatch >= 0 && pixel.mismatch <= 1, "pixel.mismatch",
          "relative standard deviation must be within [0, 1]");
  require(array.rows >= 1 && array.rows <= 65535, "array.rows", "must be from 1 to 65535");
  require(array.cols >= 1 && array.cols <= 65535, "array.cols", "must be from 1 to 65535");
  require(static_cast<long long>(array.rows) * array.cols <= kMaxArrayPixels, "array.rows",
          fmt::format("array of {} pixels, more than the {} (4096 x 4096) aesim models", 
                      static_cast<long long>(array.rows) * array.cols, kMaxArrayPixels));
  // Named with both values: a smaller array set alone keeps the preset's tile, which then no
  // longer fits.
  require(array.tile_rows >= 1 && array.tile_rows <= array.rows, "array.tile_rows",
          fmt::format("{} rows a tile must be from 1 to array.rows ({}){}", array.tile_rows, array.rows,
                      array.tile_rows > array.rows ? ": set array.tile_rows too" : ""));
  require(array.tile_cols >= 1 && array.tile_cols <= array.cols, "array.tile_cols",
          fmt::format("{} columns a tile must be from 1 to array.cols ({}){}", array.tile_cols, array.cols,
                      array.tile_cols > array.cols ? ": set array.tile_cols too" : ""));
  const AddressMap map(array);
  require(map.tiles() <= kMaxTiles, "array.tile_rows",
          fmt::format("{} tiles, more than the {} aesim models (each has its own bus and receiver)", map.tiles(),
                      kMaxTiles));
  require(map.bus_bits() + address_bits_for(map.tiles()) <= 31,
          "array.tile_rows", "tile address and tile number do not fit a 31-bit AEDAT address");
  require(bus.t_event > 0, "bus.t_event", "must be positive");
  // A clock period and a tick are whole numbers of SystemC's 1 ps step, and a run's stamps must
  // fit 64 bits: the ranges keep every conversion to integers exact.
  require(receiver.clock >= 1 && receiver.clock <= 1e12, "receiver.clock", "must be from 1 Hz to 1 THz");
  require(receiver.tick >= 1e-12 && receiver.tick <= 1, "receiver.tick", "must be from 1 ps to 1 s");
  require(bus.t_event <= 1, "bus.t_event", "must be at most 1 s");
  require(pixel.t_reset <= 1e3, "pixel.t_reset", "must be at most 1000 s");
  pixel.transfer.validate("pixel.transfer", pixel.t_reset);
  require(receiver.fifo_depth >= 1, "receiver.fifo_depth", "must be at least 1");
  // SystemC time is a 64-bit count of 1 ps steps; keep well inside it.
  require(sim.duration >= 1e-12 && sim.duration <= 1e6, "sim.duration", "must be from 1 ps to 1e6 s (SystemC's 1 ps time base)");
  require(sim.max_events >= 1 && sim.max_events <= 1e15, "sim.max_events", "must be from 1 to 1e15");
  require(sim.threads >= 0 && sim.threads <= 1024, "sim.threads", "must be from 0 (all cores) to 1024");
  require(power.vdd > 0, "power.vdd", "must be positive");
  require(power.e_pixel_event >= 0 && power.c_bus_line >= 0 && power.e_receiver_event >= 0 && power.p_static_pixel >= 0,
          "power.e_pixel_event", "energies, capacitance and static power must not be negative");
  require(light.lux >= 0, "light.lux", "must not be negative");
  require(light.responsivity > 0 && light.efficacy > 0 && light.pixel_area > 0, "light.responsivity",
          "responsivity, efficacy and pixel area must be positive");
  require(light.fill_factor > 0 && light.fill_factor <= 1, "light.fill_factor", "must be within (0, 1]");
  require(analysis.window > 0, "analysis.window", "must be positive");
  require(analysis.min_events >= 1, "analysis.min_events", "must be at least 1");
  require(sim.step >= 1e-12 && sim.step <= sim.duration, "sim.step", "must be from 1 ps to sim.duration");
  require(scene.frame_rate * sim.duration < 4e9, "scene.frame_rate", "more than 4e9 frames in sim.duration");
  require(scene.frame_rate > 0 && scene.frame_rate <= 1e9, "scene.frame_rate",
          "must be positive and at most 1 GHz");
}

void apply_toml_file(SensorConfig& config, const std::string& path, const std::string& section) {
  apply_toml_text(config, checked_toml_text(path, fmt::format("'{}'", path)), path, section);
}

void apply_toml_text(SensorConfig& config, const std::string& text, const std::string& path,
                     const std::string& section) {
  apply_toml_document(config, parse_toml_text(text, fmt::format("'{}'", path)), path, section);
}

void apply_toml_document(SensorConfig& config, const TomlValue& doc, const std::string& path, const std::string& section) {
  auto apply = [&](const std::string& key, const TomlValue& value) {
    if (key == "pixel.transfer" && value.is_table()) {
      try {
        config.pixel.transfer = transfer_from_toml(value, key);
      } catch (const InputError& e) {
        throw InputError(fmt::format("'{}': {}", path, e.what()));
      }
      return;
    }
    const std::optional<std::string> text = value.scalar_text();
    if (!text) throw InputError(fmt::format("'{}': {}: unsupported value type", path, key));
    try {
      config.set(key, *text);
    } catch (const InputError& e) {
      throw InputError(fmt::format("'{}': {}", path, e.what()));
    }
  };
  for (const auto& [name, body] : doc.as_table()) {
    if (!section.empty()) {
      apply(section + "." + name, body);
      continue;
    }
    if (name == "base" && body.is_string()) continue;  // the preset the file is read over: load_sensor
    if (!body.is_table()) {
      throw InputError(fmt::format("'{}': '{}' is not a [section]{}", path, name,
                                   name == "preset" || name == "sensor" || name == "base"
                                       ? " (the preset a file is read over is base = \"NAME\" or \"FILE.toml\")"
                                       : ""));
    }
    for (const auto& [key, value] : body.as_table()) apply(name + "." + key, value);
  }
}

ResolvedConfig SensorConfig::resolved() const {
  validate();
  ResolvedConfig c(*this);
  if (light.lux > 0) {
    c.pixel.i_max = photocurrent_from_lux(light.lux, light.responsivity, light.efficacy, light.pixel_area,
                                          light.fill_factor);
  }
  return c;
}

std::string sensors_dir() { return data_dir() + "/models/sensors"; }

std::string sensor_file(const std::string& name_or_file) {
  namespace fs = std::filesystem;
  const bool is_path = name_or_file.find('/') != std::string::npos || fs::path(name_or_file).extension() == ".toml";
  return is_path ? name_or_file : sensors_dir() + "/" + name_or_file + ".toml";
}

namespace {

// A chain of presets each read over the one it names is at most this long.
constexpr int kMostBases = 8;

SensorConfig load_sensor_file(const std::string& name_or_file, const std::string& from_folder, int depth,
                              std::vector<std::string>& chain) {
  namespace fs = std::filesystem;
  const bool is_path = name_or_file.find('/') != std::string::npos ||
                       fs::path(name_or_file).extension() == ".toml";
  // A base named by a relative path is found beside the file that names it.
  const std::string path = is_path && !from_folder.empty() && fs::path(name_or_file).is_relative()
                               ? (fs::path(from_folder) / name_or_file).string()
                               : sensor_file(name_or_file);
  if (!is_input_file(path, "sensor file")) {
    throw InputError(is_path ? fmt::format("sensor file '{}': {}", path, not_a_file(path))
                             : fmt::format("unknown sensor '{}' (no {})", name_or_file, path));
  }
  std::error_code ec;
  const std::string identity = fs::weakly_canonical(path, ec).string();
  if (std::find(chain.begin(), chain.end(), identity) != chain.end()) {
    throw InputError(fmt::format("sensor file '{}': its base presets name it again (a loop)", path));
  }
  if (depth >= kMostBases) {
    throw InputError(fmt::format("sensor file '{}': more than {} presets each read over the next (base = ...)", path,
                                 kMostBases));
  }
  chain.push_back(identity);
  const TomlValue doc = parse_toml_text(checked_toml_text(path, fmt::format("'{}'", path)), fmt::format("'{}'", path));
  SensorConfig config;
  if (const auto base = doc.as_table().find("base"); base != doc.as_table().end() && base->second.is_string()) {
    config = load_sensor_file(base->second.as_string(), fs::path(path).parent_path().string(), depth + 1, chain);
  }
  apply_toml_document(config, doc, path, "");
  return config;
}

}  // namespace

SensorConfig load_sensor(const std::string& name_or_file) {
  std::vector<std::string> chain;
  return load_sensor_file(name_or_file, "", 0, chain);
}

}  // namespace aesim
