#include "aesim/pixel/pixel_draws.hpp"

#include <random>

namespace aesim {

IntegrateFire::Sensor pixel_sensor(const PixelParams& pixel) {
  return {pixel.t_reset, pixel.shot_noise};
}

double pixel_threshold(const PixelParams& pixel, std::uint64_t seed, std::uint64_t pixel_index) {
  double threshold = pixel.threshold_charge();
  if (pixel.mismatch > 0) {
    SplitMix64 rng = stream_for(seed, Stream::Threshold, pixel_index);
    std::normal_distribution<double> normal(1.0, pixel.mismatch);
    // A threshold cannot be negative: redraw below 5 % of nominal. The truncation is invisible
    // at realistic mismatch (it cuts beyond 19 sigma at 5 %) and keeps absurd ones physical.
    double factor = normal(rng);
    while (factor < 0.05) factor = normal(rng);
    threshold *= factor;
  }
  return threshold;
}

double initial_fraction(const PixelParams& pixel, std::uint64_t seed, std::uint64_t pixel_index) {
  if (pixel.initial == InitialState::Reset) return 0.0;
  SplitMix64 rng = stream_for(seed, Stream::InitialCharge, pixel_index);
  return uniform01(rng);
}

SplitMix64 shot_noise_stream(std::uint64_t seed, std::uint64_t pixel_index) {
  return stream_for(seed, Stream::ShotNoise, pixel_index);
}

}  // namespace aesim
