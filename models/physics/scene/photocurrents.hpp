#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

// The current every pixel integrates in every frame: I = i_dark + i_max * v (docs/reference.md section 1), or
// with pixel.transfer the current that fires with the table's period (pixel/transfer_curve.hpp).
// Frame k starts at boundary k (time k * frame_period); boundary 0 is t = 0.
//
// It keeps the scene (a run's summary needs its mean after the run). A still scene's currents
// are worked out from it when asked, a pixel's once or twice a run, rather than held beside it (at
// 2048x2048 a second copy was 34 MB of a 500 MB budget); a sequence's are tabulated, since
// next_change() compares frames.
class Photocurrents {
 public:
  static constexpr std::uint64_t kNoChange = std::numeric_limits<std::uint64_t>::max();

  Photocurrents(Scene scene, PixelParams pixel);

  const Scene& scene() const { return scene_; }
  std::size_t pixels() const { return pixels_; }
  std::size_t frames() const { return scene_.frames.size(); }
  double frame_period() const { return period_; }
  bool loops() const { return scene_.loop; }
  double boundary_time(std::uint64_t boundary) const { return static_cast<double>(boundary) * period_; }
  // Which frame is shown after `boundary`: sequences loop or hold their last frame.
  std::size_t frame_at(std::uint64_t boundary) const;
  double current(std::uint64_t boundary, std::size_t pixel) const { return frame_current(frame_at(boundary), pixel); }
  // The current in frame `frame` (< frames()), without the boundary's division.
  double frame_current(std::size_t frame, std::size_t pixel) const {
    if (currents_.empty()) return pixel_.integrating_current(scene_.frames.front().pixels[pixel]);
    return currents_[frame * pixels_ + pixel];
  }
  // The first boundary after `boundary` at which this pixel's current changes, or kNoChange.
  // Pixels whose light does not change are never woken by the frame clock.
  std::uint64_t next_change(std::uint64_t boundary, std::size_t pixel) const;

 private:
  Scene scene_;
  PixelParams pixel_;
  std::size_t pixels_;
  double period_;
  std::vector<double> currents_;  // frame by frame; empty for a still scene
};

}  // namespace aesim
