#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <thread>

#include <fmt/format.h>

#include "chart/calibration_chart.hpp"
#include "commands.hpp"
#include "aesim/config/sensor_config.hpp"
#include "deck/pixel_deck.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/output/atomic_file.hpp"
#include "preset/calibrated_preset.hpp"
#include "session/pixel_calibration.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace {

CalibrationOptions parse_options(const CalibrateOptions& opt) {
  CalibrationOptions o;
  o.vdd = parse_si(opt.vdd, "V", "--vdd");
  if (!(o.vdd > 0 && o.vdd <= 100)) throw InputError(fmt::format("--vdd: {} is not a supply (0 to 100 V)", opt.vdd));
  const auto colon = opt.currents.find(':');
  if (colon == std::string::npos) throw InputError(fmt::format("--currents: expected LOW:HIGH, e.g. 1fA:1nA (got '{}')", opt.currents));
  o.i_low = parse_si(opt.currents.substr(0, colon), "A", "--currents");
  o.i_high = parse_si(opt.currents.substr(colon + 1), "A", "--currents");
  if (!(o.i_low > 0 && o.i_high > o.i_low && o.i_high <= 1)) {
    throw InputError(fmt::format("--currents: needs 0 < LOW < HIGH <= 1 A (got '{}')", opt.currents));
  }
  if (o.i_high / o.i_low > 1e12) throw InputError("--currents: more than 12 decades");
  if (opt.points < 3 || opt.points > 200) throw InputError(fmt::format("--points: {} is not from 3 to 200", opt.points));
  if (opt.mc < 0 || opt.mc == 1 || opt.mc > 1000) throw InputError(fmt::format("--mc: {} is not 0 or from 2 to 1000", opt.mc));
  if (opt.firings < 2 || opt.firings > 100) throw InputError(fmt::format("--firings: {} is not from 2 to 100", opt.firings));
  if (opt.jobs < 0 || opt.jobs > 256) throw InputError(fmt::format("--jobs: {} is not from 0 (all cores) to 256", opt.jobs));
  o.points = opt.points;
  o.mc = opt.mc;
  o.firings = opt.firings;
  o.jobs = opt.jobs > 0 ? opt.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.progress = ::isatty(STDERR_FILENO) != 0;
  return o;
}

}  // namespace

namespace {

// --bias NAME=VOLTS: a port name (one SPICE word: letters, digits, '_') and a voltage.
std::vector<PortBias> port_biases(const std::vector<std::string>& given) {
  std::vector<PortBias> out;
  for (const std::string& text : given) {
    const auto eq = text.find('=');
    const std::string name = text.substr(0, eq);
    const bool word = !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
    });
    if (eq == std::string::npos || !word) {
      throw InputError(fmt::format("--bias '{}': expected PORT=VOLTS, a port name of letters, digits and '_' (vbias=0.9V)", text));
    }
    out.push_back({name, parse_si(text.substr(eq + 1), "V", "--bias " + name)});
  }
  return out;
}

}  // namespace

int calibrate_command(const CalibrateOptions& opt) {
  CalibrationOptions options = parse_options(opt);
  const SensorConfig base = load_sensor(opt.base);
  base.validate();
  options.charge_guess = base.pixel.threshold_charge();
  if (file_extension(opt.output) != ".toml") {
    throw InputError(fmt::format("-o '{}': a preset is a .toml file", opt.output));
  }
  if (!opt.chart.empty() && file_extension(opt.chart) != ".png") {
    throw InputError(fmt::format("--chart '{}': use a .png file name", opt.chart));
  }
  const std::string chart_data =
      opt.chart.empty() ? std::string() : std::filesystem::path(opt.chart).replace_extension(".csv").string();
  const std::string deck_path = shipped_if_missing(opt.deck);
  check_output_paths({{"-o", opt.output}, {"--chart", opt.chart}, {"--chart", chart_data}}, {deck_path, sensor_file(opt.base)});
  PixelDeck deck = read_pixel_deck(deck_path, opt.subckt, opt.probe, opt.osdi, port_biases(opt.biases));
  // The mode the user's own runs of the deck have: their PDK's .spiceinit sets it, and aesim runs
  // ngspice without reading one (it runs commands).
  choose_ngbehavior(deck, opt.ngbehavior);
  // Beside the preset: the testbench and ngspice's whole log when ngspice rejects the deck.
  options.failure_log = std::filesystem::path(opt.output).replace_extension(".ngspice.log").string();

  std::fprintf(stderr, "aesim calibrate: %s (%s), %d photocurrents from %s to %s%s, vdd %s, %d ngspice at once\n",
               deck.subckt.c_str(), deck_path.c_str(), options.points, format_si(options.i_low, "A").c_str(),
               format_si(options.i_high, "A").c_str(),
               options.mc > 0 ? fmt::format(", {} Monte Carlo runs", options.mc).c_str() : "",
               format_si(options.vdd, "V").c_str(), options.jobs);
  if (!deck.ports_by_name.empty()) {
    std::fprintf(stderr, "aesim calibrate: %s's ports %s taken by their names (supply, output, ground), not in the order "
                 "vdd out gnd\n", deck.subckt.c_str(), deck.ports_by_name.c_str());
  }
  if (!deck.ngbehavior_spiceinit.empty()) {
    std::fprintf(stderr, "aesim calibrate: ngspice runs in compatibility mode ngbehavior=%s, as %s sets it (nothing "
                 "else of that file is run; --ngbehavior chooses another)\n", deck.ngbehavior.c_str(),
                 deck.ngbehavior_spiceinit.c_str());
  }
  if (!deck.left_out.empty()) {
    std::fprintf(stderr, "aesim calibrate: the runs take the deck's circuit; left out: %s\n",
                 fmt::format("{}", fmt::join(deck.left_out, ", ")).c_str());
  }
  // Before the runs, which can take minutes: the user may stop them and rerun with --vdd.
  if (const std::string note = supply_rating_note(deck, options.vdd); !note.empty()) {
    std::fprintf(stderr, "aesim calibrate: warning: %s\n", note.c_str());
  }
  const Calibration c = calibrate_pixel(deck, options);
  const SensorConfig calibrated = calibrated_config(base, c, options.vdd);
  const std::string text = calibrated_preset_text(calibrated, c, deck, opt.base, options);
  // What is written must load: read it back as any run would before it replaces anything.
  SensorConfig reread;
  apply_toml_text(reread, text, opt.output, "");
  reread.validate();

  OutputFiles files;
  files.open(opt.output) << text;
  if (!opt.chart.empty()) {
    const std::string png = files.adopt(opt.chart);
    const std::string data = files.adopt(chart_data);
    files.flush();
    draw_calibration_chart(c, calibrated.pixel, base.pixel, data, png);
  }
  files.commit();

  if (const std::string note = per_firing_energy_note(c, options.vdd); !note.empty()) {
    std::fprintf(stderr, "aesim calibrate: warning: %s\n", note.c_str());
  }
  if (const StatisticsNote note = statistics_note(deck); note.warning) {
    std::fprintf(stderr, "aesim calibrate: warning: %s\n", note.text.c_str());
  }
  std::fprintf(report_stream(), "pixel %s: Q = %s (c_int %s at dv_int %s), t_reset = %s, i_dark = %s; eq. 2 fits within %.2f %% (rms %.2f %%)\n",
              deck.subckt.c_str(), format_si(c.fit.charge, "C").c_str(), format_si(calibrated.pixel.c_int, "F").c_str(),
              format_si(calibrated.pixel.dv_int, "V").c_str(), format_si(c.fit.t_reset, "s").c_str(),
              format_si(c.fit.i_dark, "A").c_str(), 100 * c.fit.max_residual, 100 * c.fit.rms_residual);
  std::fprintf(report_stream(), "energy per firing %s (e_pixel_event %s), static %s; ",
              format_si(options.vdd * c.supply.charge_per_firing, "J").c_str(),
              format_si(calibrated.power.e_pixel_event, "J").c_str(), format_si(calibrated.power.p_static_pixel, "W").c_str());
  if (c.mismatch) std::fprintf(report_stream(), "mismatch %.4g from %d runs; ", *c.mismatch, options.mc);
  int runs = 0;
  for (const CalibrationPoint& p : c.points) runs += p.runs;
  std::fprintf(report_stream(), "%d ngspice transients in %.1f s\n", runs + options.mc, c.wall);
  std::fprintf(report_stream(), "wrote %s%s\n", opt.output.c_str(),
              opt.chart.empty() ? "" : fmt::format(", {} (its data: {})", opt.chart, chart_data).c_str());
  return 0;
}

}  // namespace aesim
