#pragma once
#include <cstddef>
#include <string>

#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

// Where a scene's light leaves the range a calibrated pixel was measured over: pixel.transfer's
// lowest and highest current are the photocurrents at which the circuit fired periodically in
// ngspice, and outside them the model extrapolates along eq. 2 (transfer_curve.hpp), except at or
// beyond the currents where the circuit was seen never to fire, where it never fires. Counted per
// pixel over every frame of the scene: a pixel below the range in some frame and above it in
// another counts in both.
struct CalibratedRangeUse {
  std::size_t pixels = 0;        // the scene's pixels
  std::size_t below = 0, above = 0;
  std::size_t silent = 0;        // of them, at or beyond a current where the circuit never fired
  double lowest = 0, highest = 0;  // A, the scene's extreme photocurrents (i_max * value)
};
// Nothing to count without a transfer table.
CalibratedRangeUse calibrated_range_use(const Scene& scene, const PixelParams& pixel);
// One line for the user when some pixel is outside (empty otherwise): how many, how far, and what
// the model does there.
std::string calibrated_range_warning(const CalibratedRangeUse& use, const PixelParams& pixel);

}  // namespace aesim
