#pragma once
#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// The work a run asks for, estimated from the scene and the parameters before anything is
// allocated for it, so that an absurd value (a huge current with no reset time, a frame rate in
// the GHz, a step of a picosecond) is refused at once instead of filling the memory or never
// ending.
struct WorkEstimate {
  double events = 0;         // expected firings: sum over pixels and frames of shown time x rate
  double frame_wakeups = 0;  // pixels woken because their light changes at a frame boundary
  double scan_steps = 0;     // pixel visits of the rungs that scan every pixel: fixed_step (pixels x
                             // steps) and queue (pixels x eq. 3 iterations of every frame)
  double process_pixels = 0; // pixels that get a SystemC process each (pixel_processes)
  double cycle_tiles = 0;    // tiles that get a clocked bus and receiver each (cycle)
};

// Rates are eq. 2 with the reset time: I / (c_int dv_int + I t_reset), the mean over mismatch
// and shot noise. `fidelity` is the rung the run resolved to.
WorkEstimate estimate_work(const SensorConfig& config, const Photocurrents& photocurrents, Fidelity fidelity);

// Throws InputError naming the figure, the key that drives it and sim.max_events (the limit,
// --max-events on the command line) when the estimate exceeds it.
void check_work(const SensorConfig& config, const Photocurrents& photocurrents, Fidelity fidelity);

// SystemC's elaboration grows faster than the number of its processes: pixel_processes set up
// 4,096 pixels in 0.06 s, 16,384 in 1.5 s and 65,536 in 93 s (a 1 ms run, 2-core VM); the cycle
// rung 1,024 tiles in 0.23 s, 4,096 in 2.1 s and 16,384 in 41 s (1.1 GB). The limits keep each
// under about ten seconds of set-up.
constexpr double kMaxProcessPixels = 1 << 15;
constexpr double kMaxCycleTiles = 1 << 12;

}  // namespace aesim
