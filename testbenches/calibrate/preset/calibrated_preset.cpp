#include "preset/calibrated_preset.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace aesim {
namespace {

std::string toml_value(const nlohmann::json& v) {
  if (v.is_string()) return nlohmann::json(v.get<std::string>()).dump();  // JSON string escapes are TOML's
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number()) return fmt::format("{:.10g}", v.get<double>());
  if (v.is_array()) {
    std::string out = "[";
    for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + toml_value(v[k]);
    return out + "]";
  }
  std::string out = "{ ";
  bool first = true;
  for (const auto& [key, value] : v.items()) {
    out += (first ? "" : ", ") + key + " = " + toml_value(value);
    first = false;
  }
  return out + " }";
}

std::string engineering(double v, const char* unit) {
  if (!std::isfinite(v)) return "-";
  return fmt::format("{:.4g} {}", v, unit);
}

}  // namespace

std::string per_firing_energy_note(const Calibration& c, double vdd) {
  const double short_by = c.fit.charge - c.supply.charge_per_firing;
  if (!(short_by > 0)) return "";
  const std::string free_fit =
      c.supply.free_charge_per_firing < 0
          ? fmt::format(" (the line fitted without bounds gives {:.4g} C per firing and {:.4g} A: a negative charge, "
                        "which the power model cannot take, so it is held at 0 and the static current refitted)",
                        c.supply.free_charge_per_firing, c.supply.free_static_current)
          : std::string();
  return fmt::format(
      "power.e_pixel_event is 0: the supply's charge per firing, {:.4g} C{}, is {:.4g} C below the threshold charge "
      "the power model counts for recharging c_int ({:.4g} C); the circuit draws that charge through paths that grow "
      "with the period (crowbar current while the node ramps through mid-rail, leakage), which the static part holds, "
      "so the model's energy per firing is {:.4g} J high",
      c.supply.charge_per_firing, free_fit, short_by, c.fit.charge, vdd * short_by);
}

SensorConfig calibrated_config(SensorConfig base, const Calibration& c, double vdd) {
  base.pixel.c_int = c.fit.charge / base.pixel.dv_int;
  base.pixel.t_reset = c.fit.t_reset;
  base.pixel.i_dark = c.fit.i_dark;
  base.pixel.transfer.current = c.current;
  base.pixel.transfer.period = c.period;
  base.pixel.transfer.charge = c.fit.charge;
  base.pixel.transfer.t_reset = c.fit.t_reset;
  base.pixel.transfer.silent_below = c.silent_below;
  base.pixel.transfer.silent_above = c.silent_above;
  if (c.mismatch) base.pixel.mismatch = *c.mismatch;
  base.power.vdd = vdd;
  base.power.e_pixel_event = std::max(0.0, vdd * (c.supply.charge_per_firing - c.fit.charge));
  base.power.p_static_pixel = vdd * c.supply.static_current;
  return base;
}

std::string calibrated_preset_text(const SensorConfig& config, const Calibration& c, const PixelDeck& deck,
                                   const std::string& base, const CalibrationOptions& o) {
  std::string text = fmt::format(
      "# Calibrated by `aesim calibrate` from the pixel circuit '{}', subcircuit {}\n"
      "# (FNV-1a 64 of the deck and its includes: {}), simulated with {}:\n"
      "# vdd {:.4g} V, {} photocurrents from {:.4g} A to {:.4g} A, {} periods each\n"
      "# ({} of them added between the log-spaced ones, where log-log interpolation would miss by over 0.2 %).\n"
      "# Base preset: {}. Every key below is the base's except the fitted ones.\n"
      "#\n"
      "# Fit of eq. 2, period = Q / (I + i_dark) + t_reset, to the measured periods (relative least squares):\n"
      "#   Q = {:.6g} C (pixel.c_int = Q / pixel.dv_int), t_reset = {:.6g} s, i_dark = {:.6g} A\n"
      "#   residuals: rms {:.3f} %, max {:.3f} %. pixel.transfer keeps the measured periods, so the model fires\n"
      "#   with the circuit's period where the circuit departs from eq. 2; its charge and t_reset are the fit's,\n"
      "#   so that a pixel resized from this one (pixel.c_int, dv_int, t_reset) scales from the circuit.\n"
      "# Supply charge per firing = {:.6g} C + {:.6g} A x period: power.e_pixel_event and power.p_static_pixel\n"
      "#   (residuals of that line: rms {:.3f} %, max {:.3f} %).\n",
      deck.given, deck.subckt, deck.hash, c.ngspice, o.vdd, c.points.size(), o.i_low, o.i_high, o.firings, c.refined, base, c.fit.charge,
      c.fit.t_reset, c.fit.i_dark, 100 * c.fit.rms_residual, 100 * c.fit.max_residual, c.supply.charge_per_firing,
      c.supply.static_current, 100 * c.supply.rms_residual, 100 * c.supply.max_residual);
  if (!deck.ngbehavior.empty()) {
    text += fmt::format("# ngspice's compatibility mode in every run: ngbehavior={} ({}).\n", deck.ngbehavior,
                        deck.ngbehavior_spiceinit.empty() ? std::string("--ngbehavior")
                                                          : "as " + deck.ngbehavior_spiceinit + " sets it");
  }
  if (!deck.biases.empty()) {
    std::string held;
    for (const PortBias& b : deck.biases) held += fmt::format("{}{} at {:.6g} V", held.empty() ? "" : ", ", b.port, b.volts);
    text += "# Ports held at a voltage in every run (--bias): " + held + ".\n";
  }
  // A warning's words as a sentence of the preset's comments.
  const auto sentence = [](const std::string& note) {
    return "# " + std::string(1, static_cast<char>(std::toupper(note[0]))) + note.substr(1) + ".\n";
  };
  if (const std::string note = per_firing_energy_note(c, o.vdd); !note.empty()) text += "# " + note + ".\n";
  if (!c.scatter_note.empty()) text += sentence(c.scatter_note);
  if (const std::string note = supply_rating_note(deck, o.vdd); !note.empty()) text += sentence(note);
  if (const StatisticsNote note = statistics_note(deck); !note.text.empty()) text += sentence(note.text);
  if (c.circuit) {
    const CircuitFit& f = *c.circuit;
    text += fmt::format(
        "# The circuit's own form, where eq. 2 does not hold (a leak of either sign, a reset that the light lengthens),\n"
        "#   period = Q / (I + i_dark) + t_r / (1 - I / I_r), fitted to the measured periods and out pulses:\n"
        "#   Q = {:.6g} C, i_dark = {:.6g} A{}, t_r = {:.6g} s, I_r = {}\n"
        "#   residuals: rms {:.3f} %, max {:.3f} %.\n",
        f.charge, f.i_dark,
        f.i_dark < 0 ? fmt::format(" (a leak: below {:.4g} A the pixel never fires)", -f.i_dark) : std::string(), f.t_r,
        std::isfinite(f.i_r) ? fmt::format("{:.6g} A (the reset never ends at and above it: the pixel latches)", f.i_r)
                             : std::string("none (the reset does not follow the light)"),
        100 * f.rms_residual, 100 * f.max_residual);
  }
  text += "# Runs use pixel.transfer, the measured periods, not the fits: the fits describe the circuit, and\n"
          "#   eq. 2's sets the keys a resized pixel scales from.\n";
  text += fmt::format(
      "# Valid from {:.4g} A to {:.4g} A, the currents at which the circuit fired periodically (pixel.transfer's\n"
      "#   ends): outside them the model extrapolates along eq. 2, and `aesim run` warns how many pixels are there.\n",
      c.current.front(), c.current.back());
  const auto silent_line = [&text](double at, const char* side, const char* key, const std::string& seen) {
    text += fmt::format("# At {:.4g} A and {} the circuit does not keep firing{}: pixel.transfer.{}, the\n"
                        "#   model's pixel is silent there too.\n",
                        at, side, seen.empty() ? "" : " (" + seen + ")", key);
  };
  if (c.silent_below > 0) silent_line(c.silent_below, "below", "silent_below", c.silent_below_seen);
  if (std::isfinite(c.silent_above)) silent_line(c.silent_above, "above", "silent_above", c.silent_above_seen);
  if (c.mismatch) {
    text += fmt::format("# Monte Carlo: {} runs at {:.4g} A: threshold-charge spread (pixel.mismatch) {:.4g}\n",
                        c.mc_periods.size(), c.mc_current, *c.mismatch);
  }
  if (std::isfinite(c.trip_level)) {
    text += fmt::format("# Probe node '{}' trips the comparator at {:.4g} V.\n", deck.probe, c.trip_level);
  }
  // The solver settings each point needed, when ngspice gave up on some under the first ones.
  bool fallback = false;
  for (std::size_t k = 1; k < c.currents_per_settings.size(); ++k) fallback = fallback || !c.currents_per_settings[k].empty();
  std::string left_out, why;
  for (const CalibrationPoint& p : c.points) {
    if (p.aborted.empty()) continue;
    left_out += fmt::format("{}{:.4g}", left_out.empty() ? "" : ", ", p.current);
    if (why.empty()) why = p.aborted;
  }
  if (fallback) {
    text += "# ngspice gave up on some transients under the first solver settings; the points were run with:\n";
    for (std::size_t k = 0; k < c.currents_per_settings.size(); ++k) {
      const std::vector<double>& currents = c.currents_per_settings[k];
      if (currents.empty()) continue;
      text += fmt::format("#   {} point{}: {}", currents.size(), currents.size() == 1 ? "" : "s", solver_level_text(k));
      if (k > 0) text += fmt::format(" ({:.4g} A)", fmt::join(currents, ", "));
      text += "\n";
    }
  }
  if (!left_out.empty()) {
    text += fmt::format("# Left out: ngspice gave up at {} A under every setting ({}).\n", left_out, why);
  }
  text += "#\n#   photocurrent   period        fit residual  pulse         comparator    supply charge\n";
  std::size_t fitted = 0;
  for (const CalibrationPoint& p : c.points) {
    const bool fired = std::isfinite(p.period);
    text += fmt::format("#   {:<14} {:<13} {:<13} {:<13} {:<13} {}\n", engineering(p.current, "A"),
                        fired                ? engineering(p.period, "s")
                        : !p.aborted.empty() ? std::string("gave up")
                        : p.inferred         ? std::string("silent beyond")
                                             : std::string("never fired"),
                        fired ? fmt::format("{:+.3f} %", 100 * c.fit.residuals[fitted]) : std::string("-"),
                        engineering(p.pulse, "s"), engineering(p.comparator_delay, "s"),
                        engineering(p.supply_charge, "C"));
    if (fired) ++fitted;
  }
  const nlohmann::json json = config.to_json();
  for (const auto& [section, body] : json.items()) {
    text += fmt::format("\n[{}]\n", section);
    for (const auto& [key, value] : body.items()) {
      if (value.is_null()) continue;
      text += fmt::format("{} = {}\n", key, toml_value(value));
    }
  }
  return text;
}

}  // namespace aesim
