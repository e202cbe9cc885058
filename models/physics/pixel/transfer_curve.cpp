#include "aesim/pixel/transfer_curve.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/toml_file.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

// A table this long is a measurement of a pixel, not a way to smuggle a scene into a preset.
constexpr std::size_t kMaxPoints = 10000;

std::vector<double> numbers(const TomlValue& array, const std::string& key, const char* field, const char* unit) {
  if (!array.is_array()) throw InputError(fmt::format("{}: '{}' must be an array of numbers", key, field));
  if (array.as_array().size() > kMaxPoints) {
    throw InputError(fmt::format("{}: more than {} points in '{}'", key, kMaxPoints, field));
  }
  std::vector<double> out;
  for (const TomlValue& v : array.as_array()) {
    if (v.is_floating()) {
      out.push_back(v.as_floating());
    } else if (v.is_integer()) {
      out.push_back(static_cast<double>(v.as_integer()));
    } else if (v.is_string()) {
      out.push_back(parse_si(v.as_string(), unit, key));
    } else {
      throw InputError(fmt::format("{}: '{}' must be an array of numbers", key, field));
    }
  }
  return out;
}

}  // namespace

double TransferCurve::period_at(double photocurrent) const {
  const auto upper = std::upper_bound(current.begin(), current.end(), photocurrent);
  if (upper == current.begin()) return period.front();
  if (upper == current.end()) return period.back();
  const std::size_t k = static_cast<std::size_t>(upper - current.begin());
  const double u = std::log(photocurrent / current[k - 1]) / std::log(current[k] / current[k - 1]);
  return std::exp(std::log(period[k - 1]) + u * std::log(period[k] / period[k - 1]));
}

double TransferCurve::integrating_current(double photocurrent, double threshold_charge, double i_dark,
                                          double t_reset) const {
  const double q = charge > 0 ? charge : threshold_charge;
  const double reset = this->t_reset >= 0 ? this->t_reset : t_reset;
  const auto effective = [&](double i) { return q / (period_at(i) - reset); };
  if (silent_at(photocurrent)) return 0;
  if (photocurrent < current.front()) {
    const double at_end = effective(current.front());
    return at_end * (photocurrent + i_dark) / (current.front() + i_dark);
  }
  if (photocurrent > current.back()) {
    const double at_end = effective(current.back());
    return at_end * (photocurrent + i_dark) / (current.back() + i_dark);
  }
  return effective(photocurrent);
}

void TransferCurve::validate(const std::string& key, double pixel_t_reset) const {
  if (empty()) return;
  const double t_reset = this->t_reset >= 0 ? this->t_reset : pixel_t_reset;
  const char* reset_key = this->t_reset >= 0 ? "its t_reset" : "pixel.t_reset";
  if (!(charge >= 0) || !std::isfinite(charge)) throw InputError(fmt::format("{}: charge must be positive", key));
  if (!std::isfinite(this->t_reset) || this->t_reset > 1e3) {
    throw InputError(fmt::format("{}: t_reset must be at most 1000 s", key));
  }
  if (current.size() != period.size()) {
    throw InputError(fmt::format("{}: {} currents but {} periods", key, current.size(), period.size()));
  }
  if (current.size() < 2) throw InputError(fmt::format("{}: needs at least 2 points", key));
  if (!(silent_below >= 0) || !(silent_below < current.front())) {
    throw InputError(fmt::format("{}: silent_below ({} A) must be below the lowest current ({} A)", key, silent_below,
                                 current.front()));
  }
  if (!(silent_above > current.back())) {
    throw InputError(fmt::format("{}: silent_above ({} A) must be above the highest current ({} A)", key, silent_above,
                                 current.back()));
  }
  for (std::size_t k = 0; k < current.size(); ++k) {
    if (!(current[k] > 0) || !std::isfinite(current[k])) {
      throw InputError(fmt::format("{}: current {} is not a positive number", key, current[k]));
    }
    if (k > 0 && !(current[k] > current[k - 1])) {
      throw InputError(fmt::format("{}: currents must increase (point {} after {})", key, current[k], current[k - 1]));
    }
    if (!(period[k] > t_reset) || !std::isfinite(period[k])) {
      throw InputError(fmt::format("{}: period {} s at {} A is not longer than {} ({} s)", key, period[k],
                                   current[k], reset_key, t_reset));
    }
  }
}

TransferCurve transfer_from_toml(const TomlValue& value, const std::string& key) {
  if (value.is_string() && (value.as_string().empty() || value.as_string() == "none")) return {};
  if (!value.is_table()) throw InputError(fmt::format("{}: expected {{ current = [...], period = [...] }}", key));
  const auto& table = value.as_table();
  for (const auto& entry : table) {
    if (entry.first != "current" && entry.first != "period" && entry.first != "charge" && entry.first != "t_reset" &&
        entry.first != "silent_below" && entry.first != "silent_above") {
      throw InputError(fmt::format(
          "{}: unknown field '{}' (expected current, period, charge, t_reset, silent_below, silent_above)", key,
          entry.first));
    }
  }
  const auto current = table.find("current"), period = table.find("period");
  if (current == table.end() || period == table.end()) {
    throw InputError(fmt::format("{}: needs both current and period", key));
  }
  TransferCurve t;
  t.current = numbers(current->second, key, "current", "A");
  t.period = numbers(period->second, key, "period", "s");
  const auto scalar = [&](const char* field, const char* unit, double& out) {
    const auto it = table.find(field);
    if (it == table.end()) return;
    const std::optional<std::string> text = it->second.scalar_text();
    if (!text || it->second.is_boolean()) throw InputError(fmt::format("{}: '{}' must be a number", key, field));
    out = parse_si(*text, unit, key);
  };
  scalar("charge", "C", t.charge);
  scalar("t_reset", "s", t.t_reset);
  scalar("silent_below", "A", t.silent_below);
  scalar("silent_above", "A", t.silent_above);
  if (table.count("charge") && !(t.charge > 0)) throw InputError(fmt::format("{}: charge must be positive", key));
  if (table.count("t_reset") && !(t.t_reset >= 0)) throw InputError(fmt::format("{}: t_reset must not be negative", key));
  return t;
}

TransferCurve transfer_from_text(const std::string& text, const std::string& key) {
  if (text.empty() || text == "none") return {};
  const std::string document = "transfer = " + text;
  check_toml_text(document, key);
  const TomlValue doc = parse_toml_text(document, key);
  return transfer_from_toml(doc.as_table().at("transfer"), key);
}

}  // namespace aesim
