#include "scene/photocurrents.hpp"

namespace aesim {

Photocurrents::Photocurrents(const Scene& scene, const PixelParams& pixel)
    : pixels_(scene.frames.front().pixels.size()), period_(scene.frame_period), loop_(scene.loop) {
  currents_.reserve(pixels_ * scene.frames.size());
  for (const Image& frame : scene.frames) {
    for (double v : frame.pixels) currents_.push_back(pixel.integrating_current(v));
  }
}

std::size_t Photocurrents::frame_at(std::uint64_t boundary) const { return frame_index(boundary, frames(), loop_); }

std::uint64_t Photocurrents::next_change(std::uint64_t boundary, std::size_t pixel) const {
  const std::size_t n = frames();
  if (n < 2) return kNoChange;
  const double now = current(boundary, pixel);
  // A held sequence changes only up to its last frame; a looped one repeats within n frames.
  const std::uint64_t last = loop_ ? boundary + n : static_cast<std::uint64_t>(n - 1);
  for (std::uint64_t b = boundary + 1; b <= last; ++b) {
    if (current(b, pixel) != now) return b;
  }
  return kNoChange;
}

}  // namespace aesim
