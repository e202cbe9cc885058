#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_settings.hpp"
#include "commands.hpp"
#include "aesim/sensor_run/sensor_run.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace {

// The run in a few lines: what ran, what it fired and delivered, the bus load and the figures a
// pixel is sized by (docs/sizing.md), which otherwise sit only in the summary.
void print_report(const RunOptions& opt, const RunReport& r) {
  const ResolvedConfig& config = r.config;
  const AddressMap map(config.array);
  std::fprintf(report_stream(), "aesim run: sensor %s, %dx%d pixels in %d tiles of %dx%d, scene %s (%dx%d%s%s)\n", opt.sensor.c_str(),
              map.cols(), map.rows(), map.tiles(), config.array.tile_cols, config.array.tile_rows, r.scene.c_str(),
              r.scene_width, r.scene_height, r.scene_frames > 1 ? fmt::format(", {} frames", r.scene_frames).c_str() : "",
              r.default_scene ? ", the default" : "");
  std::fprintf(report_stream(), "  simulated %s at fidelity %s%s, bus %s (tau %s%s), in %.3g s wall time\n",
              format_si(config.sim.duration, "s").c_str(), to_string(r.fidelity),
              config.sim.fidelity == Fidelity::Auto ? " (chosen by auto)" : "", to_string(config.bus.access),
              format_si(r.facts.tau_s, "s").c_str(), r.fidelity == Fidelity::Cycle ? " measured" : "", r.facts.wall_time_s);
  const TileCounters& total = r.totals;
  std::fprintf(report_stream(), "  events: %llu fired (%s), %llu delivered, %llu lost to collisions (%.2f %%), %llu ghosts\n",
              static_cast<unsigned long long>(total.fired),
              format_si(static_cast<double>(total.fired) / config.sim.duration, "events/s").c_str(),
              static_cast<unsigned long long>(total.delivered), static_cast<unsigned long long>(total.collided),
              100.0 * total.collision_fraction(), static_cast<unsigned long long>(total.ghost));
  std::fprintf(report_stream(), "  bus load per tile: G = %.4g offered, S = %.4g delivered\n", r.summary["offered_load"].get<double>(),
              r.summary["throughput"].get<double>());
  const auto figure = [&r](const char* key) {
    const nlohmann::json& v = r.summary[key];
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  const double psnr = figure("psnr_db");
  std::fprintf(report_stream(), "  sizing: power %s (%s per tile, %s of it static), PSNR %s and %.1f %% of pixels firing %d+ times "
              "within the %s readout window\n",
              format_si(figure("power_w"), "W").c_str(), format_si(figure("power_per_tile_w"), "W").c_str(),
              format_si(figure("power_static_w"), "W").c_str(),
              std::isfinite(psnr) ? fmt::format("{:.1f} dB", psnr).c_str()
              : std::isinf(psnr)  ? "infinite (the reconstruction equals the scene)"
                                  : "not computed",
              100.0 * figure("dynamic_range_covered"), config.analysis.min_events,
              format_si(config.analysis.window, "s").c_str());
  std::string written;
  for (const std::string& path : r.written) written += (written.empty() ? "" : ", ") + path;
  if (!r.rtl_traces.empty()) {
    written += fmt::format(" (and RTL internals in {} .. tile{}.rtl.vcd)", r.rtl_traces.front(), r.rtl_traces.size() - 1);
  }
  std::fprintf(report_stream(), "  wrote %s\n", written.c_str());
}

}  // namespace

int run_command(RunOptions opt) {
  RunSpec spec;
  spec.sensor = opt.sensor;
  spec.scene = opt.scene;
  spec.settings = command_settings(opt.sets, opt.duration, opt.max_events);
  const bool no_outputs_named = opt.out.empty() && opt.csv.empty() && opt.recon.empty() && opt.summary.empty();
  spec.out = no_outputs_named ? "out/events.aedat" : opt.out;
  spec.csv = no_outputs_named ? "out/events.csv" : opt.csv;
  spec.recon = no_outputs_named ? "out/recon.png" : opt.recon;
  spec.summary = no_outputs_named ? "out/summary.json" : opt.summary;
  spec.truth = opt.truth;
  spec.vcd = opt.vcd;
  spec.vcd_from = opt.vcd_from;
  spec.vcd_to = opt.vcd_to;
  spec.aedat_layout = opt.aedat_layout;
  spec.aedat4_compression = opt.aedat4_compression;
  spec.raw_encoding = opt.raw_encoding;
  const RunReport report = run_sensor(spec);
  for (const std::string& w : report.warnings) std::fprintf(stderr, "aesim: warning: %s\n", w.c_str());
  print_report(opt, report);
  return 0;
}

}  // namespace aesim
