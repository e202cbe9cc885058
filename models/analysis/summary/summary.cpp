#include "aesim/summary/summary.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "aesim/compare/fidelity_errors.hpp"
#include "aesim/power/power_model.hpp"

namespace aesim {
namespace {

// Pixel rates, coverage within the readout window and power (models/physics/power/power_model.hpp).
void add_sizing(nlohmann::json& s, const SensorConfig& config, const EventLog& log, const RunFacts& facts) {
  const std::vector<EventLog::PixelCounts>& pixels = log.pixel_counts();
  if (pixels.empty()) return;
  const double t = facts.sim_time_s;
  std::uint32_t lo = pixels[0].fired, hi = pixels[0].fired;
  double sum = 0;
  std::size_t covered = 0;
  for (const EventLog::PixelCounts& p : pixels) {
    lo = std::min(lo, p.fired);
    hi = std::max(hi, p.fired);
    sum += p.fired;
    covered += p.fired_in_window >= static_cast<std::uint32_t>(config.analysis.min_events) ? 1 : 0;
  }
  s["pixel_rate_min_hz"] = lo / t;
  s["pixel_rate_mean_hz"] = sum / static_cast<double>(pixels.size()) / t;
  s["pixel_rate_max_hz"] = hi / t;
  s["dynamic_range_covered"] = static_cast<double>(covered) / static_cast<double>(pixels.size());

  const TileCounters total = log.totals();
  PowerInputs in;
  in.c_int = config.pixel.c_int;
  in.dv_int = config.pixel.dv_int;
  in.firings = total.fired;
  in.transactions = total.fired - total.pending;  // every fired event drives its bus once
  in.address_ones = log.address_ones();
  in.pixels = pixels.size();
  in.duration = t;
  const PowerResult r = power(config.power, in);
  s["energy_per_event_j"] = r.energy_per_event;
  s["power_w"] = r.total_power;
  s["power_static_w"] = r.static_power;
  s["power_per_tile_w"] = r.total_power / static_cast<double>(log.tiles().size());
}

// The PSNR of the histogram of real output events within the window against the scene, each
// normalised to its peak (histogram_image and the scene divided by its peak, as psnr_db takes
// them), read in place: at 2048x2048 the two images would be 64 MB of fresh memory, whose first
// touch would be most of the summary's time.
double window_psnr_db(const std::vector<EventLog::PixelCounts>& pixels, const Image& scene) {
  std::uint32_t most = 0;
  for (const EventLog::PixelCounts& p : pixels) most = std::max(most, p.output_in_window);
  const double count_peak = most, scene_peak = *std::max_element(scene.pixels.begin(), scene.pixels.end());
  return psnr_db(
      scene.pixels.size(),
      [&pixels, count_peak](std::size_t i) {
        const double v = pixels[i].output_in_window;
        return count_peak > 0 ? v / count_peak : v;
      },
      [&scene, scene_peak](std::size_t i) { return scene_peak > 0 ? scene.pixels[i] / scene_peak : scene.pixels[i]; });
}

}  // namespace

nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts, const Image* scene) {
  const TileCounters total = log.totals();
  const double buses = static_cast<double>(log.tiles().size());
  const double per_bus_rate = 1.0 / (buses * facts.sim_time_s);
  nlohmann::json tiles = nlohmann::json::array();
  double worst_load = 0, worst_loss = 0;
  for (const TileCounters& t : log.tiles()) {
    const double load = static_cast<double>(t.fired) / facts.sim_time_s * facts.tau_s;
    tiles.push_back({{"fired", t.fired}, {"delivered", t.delivered}, {"collided", t.collided},
                     {"ghost", t.ghost}, {"dropped", t.dropped}, {"pending", t.pending},
                     {"offered_load", load}, {"collision_fraction", t.collision_fraction()}});
    worst_load = std::max(worst_load, load);
    worst_loss = std::max(worst_loss, t.collision_fraction());
  }
  const LatencyStats latency = log.latency();
  nlohmann::json summary = {
      {"events_fired", total.fired},
      {"events_delivered", total.delivered},
      {"events_collided", total.collided},
      {"events_ghost", total.ghost},
      {"events_dropped", total.dropped},
      {"events_pending", total.pending},
      {"offered_load", static_cast<double>(total.fired) * per_bus_rate * facts.tau_s},
      {"throughput", static_cast<double>(total.delivered - total.ghost) * per_bus_rate * facts.tau_s},
      {"collision_fraction", total.collision_fraction()},
      {"offered_load_max_tile", worst_load},
      {"collision_fraction_max_tile", worst_loss},
      {"latency_mean_s", latency.mean},
      {"latency_p99_s", latency.p99},
      {"latency_max_s", latency.max},
      {"tau_s", facts.tau_s},
      {"sim_time_s", facts.sim_time_s},
      {"wall_time_s", facts.wall_time_s},
      {"fidelity", to_string(facts.fidelity)},
      {"protocol_violations", facts.protocol_violations},
      {"receiver_clock_edges", facts.receiver_clock_edges},
      {"receiver_tick_s", facts.tick_s},
      {"scoreboard_beats", facts.scoreboard_beats},
      {"scoreboard_mismatches", facts.scoreboard_mismatches},
      {"fixed_step_multi_fire_steps", facts.multi_fire_steps},
      {"queue_empty_lit_frames", facts.empty_queue_frames},
      {"tiles", tiles},
      {"sensor", config.to_json()},
  };
  add_sizing(summary, config, log, facts);
  if (scene && !log.pixel_counts().empty()) summary["psnr_db"] = window_psnr_db(log.pixel_counts(), *scene);
  return summary;
}

}  // namespace aesim
