#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace {

// A key's value in the preset as a designer would type it back with --set.
std::string value_text(const nlohmann::json& v, const std::string& unit) {
  if (v.is_null()) return "none";
  const bool si = !unit.empty() && unit.find('|') == std::string::npos && unit != "table";
  if (si && v.is_number()) return format_si(v.get<double>(), unit);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_object()) return fmt::format("table of {} points", v["current"].size());
  if (v.is_number_float()) return fmt::format("{:g}", v.get<double>());
  return v.dump();
}

}  // namespace

int config_keys_command(const std::string& sensor, bool markdown) {
  const SensorConfig config = load_sensor(sensor);
  const nlohmann::json values = config.to_json();
  const std::vector<KeyInfo> keys = SensorConfig::key_table();
  if (markdown) {
    fmt::print(report_stream(), "| key | unit or values | {} | meaning |\n|---|---|---|---|\n", sensor);
  }
  std::size_t key_width = 0, unit_width = 0, value_width = 0;
  std::vector<std::string> shown;
  for (const KeyInfo& k : keys) {
    const auto dot = k.key.find('.');
    shown.push_back(value_text(values[k.key.substr(0, dot)][k.key.substr(dot + 1)], k.unit));
    key_width = std::max(key_width, k.key.size());
    unit_width = std::max(unit_width, k.unit.size());
    value_width = std::max(value_width, shown.back().size());
  }
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const KeyInfo& k = keys[i];
    if (markdown) {
      // A '|' would end the table's cell.
      std::string unit = k.unit.empty() ? "-" : k.unit;
      for (auto bar = unit.find('|'); bar != std::string::npos; bar = unit.find('|')) unit.replace(bar, 1, ", ");
      fmt::print(report_stream(), "| `{}` | {} | {} | {} |\n", k.key, unit, shown[i], k.meaning);
    } else {
      fmt::print(report_stream(), "{:<{}}  {:<{}}  {:<{}}  {}\n", k.key, key_width, k.unit.empty() ? "-" : k.unit, unit_width, shown[i],
                 value_width, k.meaning);
    }
  }
  return 0;
}

}  // namespace aesim
