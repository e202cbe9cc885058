#include "aesim/scene/photocurrents.hpp"

#include <utility>

namespace aesim {

Photocurrents::Photocurrents(Scene scene, PixelParams pixel)
    : scene_(std::move(scene)),
      pixel_(std::move(pixel)),
      pixels_(scene_.frames.front().pixels.size()),
      period_(scene_.frame_period) {
  if (scene_.frames.size() < 2) return;
  currents_.reserve(pixels_ * scene_.frames.size());
  for (const Image& frame : scene_.frames) {
    for (double v : frame.pixels) currents_.push_back(pixel_.integrating_current(v));
  }
}

std::size_t Photocurrents::frame_at(std::uint64_t boundary) const {
  return frame_index(boundary, frames(), scene_.loop);
}

std::uint64_t Photocurrents::next_change(std::uint64_t boundary, std::size_t pixel) const {
  const std::size_t n = frames();
  if (n < 2) return kNoChange;
  // A held sequence changes only up to its last frame; a looped one repeats within n frames. The
  // frames are walked by index (one division, not one a frame: this runs for every pixel the
  // light changes at each change).
  const std::size_t start = frame_at(boundary);
  if (!scene_.loop && start == n - 1) return kNoChange;
  const double* column = currents_.data() + pixel;
  const double now = column[start * pixels_];
  std::size_t f = start;
  for (std::uint64_t b = boundary + 1, last = scene_.loop ? boundary + n : static_cast<std::uint64_t>(n - 1); b <= last;
       ++b) {
    f = f + 1 == n ? 0 : f + 1;
    if (column[f * pixels_] != now) return b;
  }
  return kNoChange;
}

}  // namespace aesim
