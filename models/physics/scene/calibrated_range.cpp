#include "aesim/scene/calibrated_range.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "aesim/units/si_units.hpp"

namespace aesim {

CalibratedRangeUse calibrated_range_use(const Scene& scene, const PixelParams& pixel) {
  CalibratedRangeUse use;
  if (pixel.transfer.empty() || scene.frames.empty()) return use;
  const double lo = pixel.transfer.current.front(), hi = pixel.transfer.current.back();
  use.pixels = scene.frames.front().pixels.size();
  const TransferCurve& t = pixel.transfer;
  std::vector<unsigned char> seen(use.pixels, 0);  // bit 0: below, bit 1: above, bit 2: silent
  use.lowest = pixel.i_max * scene.frames.front().pixels.front();
  use.highest = use.lowest;
  for (const Image& frame : scene.frames) {
    for (std::size_t i = 0; i < frame.pixels.size() && i < use.pixels; ++i) {
      const double current = pixel.i_max * frame.pixels[i];
      use.lowest = std::min(use.lowest, current);
      use.highest = std::max(use.highest, current);
      if (current < lo) seen[i] |= 1;
      if (current > hi) seen[i] |= 2;
      if (t.silent_at(current)) seen[i] |= 4;
    }
  }
  for (const unsigned char s : seen) {
    use.below += s & 1;
    use.above += (s >> 1) & 1;
    use.silent += (s >> 2) & 1;
  }
  return use;
}

std::string calibrated_range_warning(const CalibratedRangeUse& use, const PixelParams& pixel) {
  if (use.below == 0 && use.above == 0) return "";
  std::vector<std::string> parts;
  if (use.below > 0) parts.push_back(fmt::format("{} below it, down to {}", use.below, format_si(use.lowest, "A")));
  if (use.above > 0) parts.push_back(fmt::format("{} above it, up to {}", use.above, format_si(use.highest, "A")));
  const TransferCurve& t = pixel.transfer;
  std::string silent;
  if (use.silent > 0) {
    std::vector<std::string> where;
    if (t.silent_below > 0) where.push_back(fmt::format("at or below {}", format_si(t.silent_below, "A")));
    if (std::isfinite(t.silent_above)) where.push_back(fmt::format("at or above {}", format_si(t.silent_above, "A")));
    silent = fmt::format("; {} of them {}, where the circuit does not keep firing, do not fire in the model either",
                         use.silent, fmt::join(where, " or "));
  }
  return fmt::format(
      "pixel.transfer was calibrated from {} to {}; of the scene's {} pixels, {}: there the model extrapolates "
      "along eq. 2 rather than the circuit's measured periods (aesim calibrate --currents can widen the table){}",
      format_si(t.current.front(), "A"), format_si(t.current.back(), "A"), use.pixels, fmt::join(parts, "; "), silent);
}

}  // namespace aesim
