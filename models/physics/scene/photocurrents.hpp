#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include "config/sensor_config.hpp"
#include "scene/scene.hpp"

namespace aesim {

// The current every pixel integrates in every frame: I = i_dark + i_max * v (SPEC section 1), or
// with pixel.transfer the current that fires with the table's period (pixel/transfer_curve.hpp).
// Frame k starts at boundary k (time k * frame_period); boundary 0 is t = 0.
class Photocurrents {
 public:
  static constexpr std::uint64_t kNoChange = std::numeric_limits<std::uint64_t>::max();

  Photocurrents(const Scene& scene, const PixelParams& pixel);

  std::size_t pixels() const { return pixels_; }
  std::size_t frames() const { return currents_.size() / pixels_; }
  double frame_period() const { return period_; }
  bool loops() const { return loop_; }
  double boundary_time(std::uint64_t boundary) const { return static_cast<double>(boundary) * period_; }
  // Which frame is shown after `boundary`: sequences loop or hold their last frame.
  std::size_t frame_at(std::uint64_t boundary) const;
  double current(std::uint64_t boundary, std::size_t pixel) const {
    return currents_[frame_at(boundary) * pixels_ + pixel];
  }
  // The first boundary after `boundary` at which this pixel's current changes, or kNoChange.
  // Pixels whose light does not change are never woken by the frame clock.
  std::uint64_t next_change(std::uint64_t boundary, std::size_t pixel) const;

 private:
  std::size_t pixels_;
  double period_;
  bool loop_;
  std::vector<double> currents_;
};

}  // namespace aesim
