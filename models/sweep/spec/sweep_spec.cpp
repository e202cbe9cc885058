#include "aesim/spec/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "aesim/files/data_dir.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/text/nearest_name.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/files/toml_file.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/random/splitmix64.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kMaxPoints = 100000;

// Tables in key order (std::map), so that axes vary in a defined order whatever the hashing.
using Value = TomlValue;
using Table = std::map<std::string, TomlValue>;

std::string scalar_text(const Value& v, const std::string& where) {
  const std::optional<std::string> text = v.scalar_text();
  if (!text) throw InputError(fmt::format("{}: expected a string, number or boolean", where));
  return *text;
}

// A range table {from, to, points, scale = "linear"|"log"}, in the key's unit.
std::vector<std::string> expand_range(const Table& t, const std::string& where) {
  for (const auto& [k, v] : t) {
    if (k != "from" && k != "to" && k != "points" && k != "scale") {
      throw InputError(fmt::format("{}: unknown range field '{}' (use from, to, points, scale)", where, k));
    }
  }
  if (!t.count("from") || !t.count("to") || !t.count("points")) {
    throw InputError(fmt::format("{}: a range needs from, to and points", where));
  }
  const std::string from_text = scalar_text(t.at("from"), where + ".from");
  const std::string to_text = scalar_text(t.at("to"), where + ".to");
  // The unit, if any, is whatever follows the number; both ends must share it.
  auto split = [&](const std::string& s) {
    std::size_t i = 0;
    while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.' || s[i] == 'e' ||
                            s[i] == 'E' || s[i] == '-' || s[i] == '+')) {
      ++i;
    }
    std::string unit = s.substr(i);
    unit.erase(0, unit.find_first_not_of(' '));
    // Strip an SI prefix so "2us" and "2ms" both have unit "s".
    if (unit.size() > 1 && std::string("yzafpnumkMGT").find(unit[0]) != std::string::npos) unit.erase(0, 1);
    if (unit.rfind("\xC2\xB5", 0) == 0) unit.erase(0, 2);
    return unit;
  };
  const std::string unit = split(from_text);
  if (split(to_text) != unit) throw InputError(fmt::format("{}: from and to have different units", where));
  const double from = parse_si(from_text, unit, where + ".from");
  const double to = parse_si(to_text, unit, where + ".to");
  const Value& pv = t.at("points");
  if (!pv.is_integer() || pv.as_integer() < 2 || pv.as_integer() > 10000) {
    throw InputError(fmt::format("{}: points must be a whole number from 2 to 10000", where));
  }
  const int points = static_cast<int>(pv.as_integer());
  const std::string scale = t.count("scale") ? scalar_text(t.at("scale"), where + ".scale") : "linear";
  if (scale != "linear" && scale != "log") throw InputError(fmt::format("{}: scale must be linear or log", where));
  if (scale == "log" && (from <= 0 || to <= 0)) throw InputError(fmt::format("{}: a log range needs positive ends", where));
  std::vector<std::string> values;
  for (int i = 0; i < points; ++i) {
    const double f = static_cast<double>(i) / (points - 1);
    const double v = scale == "log" ? from * std::pow(to / from, f) : from + (to - from) * f;
    values.push_back(fmt::format("{:.9g}{}", v, unit));
  }
  return values;
}

std::vector<std::string> expand_values(const Value& v, const std::string& where) {
  if (v.is_array()) {
    std::vector<std::string> out;
    for (const Value& item : v.as_array()) out.push_back(scalar_text(item, where));
    if (out.empty()) throw InputError(fmt::format("{}: empty list", where));
    return out;
  }
  if (v.is_table()) return expand_range(v.as_table(), where);
  return {scalar_text(v, where)};
}

std::string resolve_path(const std::string& p, const fs::path& spec_dir) {
  if (fs::path(p).is_absolute()) return p;
  std::error_code ec;
  if (is_input_file((spec_dir / p).string(), "sweep spec path") || is_input_folder((spec_dir / p).string(), "sweep spec path")) {
    const fs::path canonical = fs::weakly_canonical(spec_dir / p, ec);
    if (!ec) return canonical.string();
  }
  return (fs::path(data_dir()) / p).string();
}

}  // namespace

SweepSpec load_sweep_spec(const std::string& path) {
  require_input_file(path, "sweep spec");
  const Value doc = parse_toml_file(path, fmt::format("sweep spec '{}'", path));
  const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  SweepSpec spec;
  spec.path = path;
  std::vector<std::pair<std::string, std::string>> fixed;
  const Value* groups = nullptr;
  for (const auto& [key, value] : doc.as_table()) {
    const std::string where = fmt::format("sweep spec '{}': {}", path, key);
    if (key == "sensor") spec.sensor = scalar_text(value, where);
    else if (key == "duration") spec.duration = scalar_text(value, where);
    else if (key == "chart") {
      const std::string given = scalar_text(value, where);
      spec.chart = resolve_path(given, dir);
      if (!is_input_file(spec.chart, "chart script")) {
        if (fs::path(given).is_absolute()) {
          throw InputError(fmt::format("{}: chart script '{}': {}", where, spec.chart, not_a_file(spec.chart)));
        }
        throw InputError(fmt::format("{}: chart script '{}' is neither in the spec's folder '{}' nor in the aesim tree "
                                     "'{}' (the shipped charts are scripts/charts/NAME.gp)",
                                     where, given, dir.string(), data_dir()));
      }
    }
    else if (key == "jobs") {
      if (!value.is_integer() || value.as_integer() < 0 || value.as_integer() > 1024) {
        throw InputError(where + ": must be a whole number from 0 (all cores) to 1024");
      }
      spec.jobs = static_cast<int>(value.as_integer());
    } else if (key == "set") {
      if (!value.is_table()) throw InputError(where + ": must be a table of key = value");
      for (const auto& [k, v] : value.as_table()) fixed.emplace_back(k, scalar_text(v, where + "." + k));
    } else if (key == "group") {
      groups = &value;
    } else if (key == "constraints") {
      if (!value.is_table()) throw InputError(where + ": must be a table of column = \"<= value\"");
      for (const auto& [column, bound] : value.as_table()) {
        try {
          spec.constraints.push_back(parse_constraint(column, scalar_text(bound, where + "." + column)));
        } catch (const InputError& e) {
          throw InputError(fmt::format("sweep spec '{}': {}", path, e.what()));
        }
      }
    } else {
      throw InputError(fmt::format("{}: unknown top-level key (use sensor, duration, jobs, chart, [set], [constraints], [[group]])", where));
    }
  }
  if (groups == nullptr || !groups->is_array() || groups->as_array().empty()) {
    throw InputError(fmt::format("sweep spec '{}': no [[group]] of design points", path));
  }
  if (spec.sensor.find('/') != std::string::npos || fs::path(spec.sensor).extension() == ".toml") {
    spec.sensor = resolve_path(spec.sensor, dir);
  }
  const SensorConfig base = load_sensor(spec.sensor);

  std::size_t group_index = 0;
  for (const Value& group : groups->as_array()) {
    ++group_index;
    if (!group.is_table()) throw InputError(fmt::format("sweep spec '{}': group {} is not a table", path, group_index));
    std::string name = fmt::format("{}", group_index);
    std::vector<std::string> scenes = {kDefaultScene};
    long long samples = 0;
    std::uint64_t sample_seed = 1;
    std::vector<std::pair<std::string, std::vector<std::string>>> axes;
    for (const auto& [key, value] : group.as_table()) {
      const std::string where = fmt::format("sweep spec '{}': group {}: {}", path, group_index, key);
      if (key == "name") name = scalar_text(value, where);
      else if (key == "scene") scenes = expand_values(value, where);
      else if (key == "samples" || key == "seed") {
        if (!value.is_integer() || value.as_integer() < (key == "samples" ? 1 : 0) || value.as_integer() > 100000) {
          throw InputError(fmt::format("{}: a whole number{}", where, key == "samples" ? " from 1 to 100000" : ""));
        }
        if (key == "samples") samples = value.as_integer();
        else sample_seed = static_cast<std::uint64_t>(value.as_integer());
      }
      else {
        const auto& known = SensorConfig::keys();
        if (std::find(known.begin(), known.end(), key) == known.end()) {
          throw InputError(fmt::format("{}: unknown key{}", where, did_you_mean(key, known)));
        }
        axes.emplace_back(key, expand_values(value, where));
      }
    }
    for (std::string& s : scenes) s = resolve_path(s, dir);
    for (const auto& axis : axes) {
      if (std::find(spec.swept_keys.begin(), spec.swept_keys.end(), axis.first) == spec.swept_keys.end()) {
        spec.swept_keys.push_back(axis.first);
      }
    }
    // Cartesian product, last axis fastest, scenes outermost; or seeded draws from it.
    // Counted against the limit factor by factor, so that no product can wrap around.
    std::size_t count = scenes.size();
    auto grow = [&](std::size_t factor) {
      count = factor != 0 && count > kMaxPoints / factor ? kMaxPoints + 1 : count * factor;
    };
    for (const auto& axis : axes) grow(samples > 0 ? 1 : axis.second.size());
    if (samples > 0) grow(static_cast<std::size_t>(samples));
    if (count > kMaxPoints - spec.points.size()) {
      throw InputError(fmt::format("sweep spec '{}': more than {} design points", path, kMaxPoints));
    }
    if (samples > 0) {
      SplitMix64 rng(sample_seed);
      for (const std::string& scene : scenes) {
        for (long long k = 0; k < samples; ++k) {
          SweepPoint p{name, scene, fixed};
          for (const auto& axis : axes) {
            const auto pick = static_cast<std::size_t>(uniform01(rng) * static_cast<double>(axis.second.size()));
            p.sets.emplace_back(axis.first, axis.second[std::min(pick, axis.second.size() - 1)]);
          }
          spec.points.push_back(std::move(p));
        }
      }
      continue;
    }
    for (const std::string& scene : scenes) {
      std::vector<std::size_t> index(axes.size(), 0);
      for (;;) {
        SweepPoint p{name, scene, fixed};
        for (std::size_t a = 0; a < axes.size(); ++a) p.sets.emplace_back(axes[a].first, axes[a].second[index[a]]);
        spec.points.push_back(std::move(p));
        std::size_t a = axes.size();
        while (a > 0 && ++index[a - 1] == axes[a - 1].second.size()) index[--a] = 0;
        if (a == 0) break;
      }
    }
  }

  // Every scene must read, and every point make a valid sensor, before any process starts.
  std::vector<std::string> checked;
  for (const SweepPoint& p : spec.points) {
    if (std::find(checked.begin(), checked.end(), p.scene) != checked.end()) continue;
    try {
      read_frames(find_scene(p.scene));
    } catch (const InputError& e) {
      throw InputError(fmt::format("sweep spec '{}': group {}: {}", path, p.group, e.what()));
    }
    checked.push_back(p.scene);
  }
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    const SweepPoint& p = spec.points[i];
    try {
      std::vector<Setting> settings(p.sets.begin(), p.sets.end());
      if (!spec.duration.empty()) settings.emplace_back("sim.duration", spec.duration);
      configure_run(base, find_scene(p.scene), settings);
    } catch (const InputError& e) {
      throw InputError(fmt::format("sweep spec '{}': group {}, point {}: {}", path, p.group, i + 1, e.what()));
    }
  }
  return spec;
}

}  // namespace aesim
