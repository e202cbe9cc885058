#include "aesim/rungs/run_budget.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

WorkEstimate estimate_work(const SensorConfig& config, const Photocurrents& photocurrents, Fidelity fidelity) {
  WorkEstimate w;
  const std::size_t frames = photocurrents.frames(), pixels = photocurrents.pixels();
  const double duration = config.sim.duration;
  const double q = config.pixel.threshold_charge();
  const std::vector<double> shown =
      frame_exposures(frames, frames > 1 ? photocurrents.frame_period() : duration, photocurrents.loops(), duration);
  for (std::size_t f = 0; f < frames; ++f) {
    if (shown[f] == 0) continue;
    double rate_sum = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
      const double current = photocurrents.frame_current(f, i);
      // Written so that a huge current gives a huge rate, never inf/inf.
      if (current > 0) rate_sum += 1.0 / (q / current + config.pixel.t_reset);
    }
    w.events += rate_sum * shown[f];
  }
  if (frames > 1) {
    // Boundaries b = 1 .. started-1 show frame index(b); each wakes the pixels whose light
    // differs from the frame before.
    std::vector<double> changed(frames, 0);
    for (std::size_t f = 0; f < frames; ++f) {
      const std::size_t before = f == 0 ? frames - 1 : f - 1;
      for (std::size_t i = 0; i < pixels; ++i)
        changed[f] += photocurrents.frame_current(f, i) != photocurrents.frame_current(before, i) ? 1 : 0;
    }
    const double boundaries = std::ceil(duration / photocurrents.frame_period());
    if (photocurrents.loops()) {
      for (std::size_t f = 0; f < frames; ++f) w.frame_wakeups += changed[f] * boundaries / static_cast<double>(frames);
    } else {
      for (std::size_t f = 1; f < frames && static_cast<double>(f) < boundaries; ++f) w.frame_wakeups += changed[f];
    }
  }
  if (fidelity == Fidelity::FixedStep) w.scan_steps = static_cast<double>(pixels) * std::ceil(duration / config.sim.step);
  if (fidelity == Fidelity::Queue && config.pixel.i_max > 0) {
    const double period = frames > 1 ? photocurrents.frame_period() : duration;
    const double f_max = config.pixel.i_max / q;
    for (std::size_t f = 0; f < frames; ++f) {
      double p_max = 0;
      for (std::size_t i = 0; i < pixels; ++i)
        p_max = std::max(p_max, photocurrents.frame_current(f, i) - config.pixel.i_dark);
      const double showings = std::ceil(shown[f] / period);
      w.scan_steps += showings * (std::round(f_max * p_max / config.pixel.i_max * period) + 1) * static_cast<double>(pixels);
    }
  }
  if (fidelity == Fidelity::PixelProcesses) w.process_pixels = static_cast<double>(pixels);
  if (fidelity == Fidelity::Cycle) {
    const double across = std::ceil(static_cast<double>(config.array.cols) / config.array.tile_cols);
    const double down = std::ceil(static_cast<double>(config.array.rows) / config.array.tile_rows);
    w.cycle_tiles = across * down;
  }
  return w;
}

void check_work(const SensorConfig& config, const Photocurrents& photocurrents, Fidelity fidelity) {
  const WorkEstimate w = estimate_work(config, photocurrents, fidelity);
  const double limit = config.sim.max_events;
  auto refuse = [&](const char* key, const std::string& what, const std::string& advice) {
    throw InputError(fmt::format("{}: the run would {} (limit {:.3g}, sim.max_events or --max-events); {}", key, what,
                                 limit, advice));
  };
  if (!(w.events <= limit)) {
    refuse("pixel.i_max",
           std::isfinite(w.events) ? fmt::format("fire about {:.3g} events", w.events)
                                   : std::string("fire without bound (an integration time rounds to zero)"),
           "shorten sim.duration, dim the scene (pixel.i_max), raise pixel.c_int*dv_int or pixel.t_reset, or raise the "
           "limit");
  }
  if (!(w.frame_wakeups <= limit)) {
    refuse("scene.frame_rate", fmt::format("wake pixels {:.3g} times at frame changes", w.frame_wakeups),
           "lower scene.frame_rate or shorten sim.duration");
  }
  // A pixel visit costs about a hundredth of an event (measured: ~1 ns against ~100 ns).
  if (!(w.scan_steps <= limit * 100)) {
    throw InputError(fmt::format("{}: the {} rung would visit pixels {:.3g} times (limit {:.3g}: a hundred per "
                                 "sim.max_events); {}",
                                 fidelity == Fidelity::FixedStep ? "sim.step" : "sim.fidelity", to_string(fidelity),
                                 w.scan_steps, limit * 100,
                                 fidelity == Fidelity::FixedStep ? "use a longer sim.step or raise the limit"
                                                                 : "use sim.fidelity=event or raise the limit"));
  }
  if (w.process_pixels > kMaxProcessPixels) {
    throw InputError(fmt::format("sim.fidelity: pixel_processes elaborates a SystemC process per pixel; {:.0f} pixels "
                                 "is more than its {:.0f}, whose set-up alone takes seconds (use sim.fidelity=event)",
                                 w.process_pixels, kMaxProcessPixels));
  }
  if (w.cycle_tiles > kMaxCycleTiles) {
    throw InputError(fmt::format("sim.fidelity: the cycle rung elaborates a clocked bus and receiver per tile; {:.0f} "
                                 "tiles is more than its {:.0f}, whose set-up alone takes seconds (use larger "
                                 "array.tile_rows/tile_cols, or sim.fidelity=event)",
                                 w.cycle_tiles, kMaxCycleTiles));
  }
}

}  // namespace aesim
