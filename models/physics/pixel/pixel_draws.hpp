#pragma once
#include <cstdint>

#include "aesim/config/sensor_config.hpp"
#include "aesim/pixel/integrate_fire.hpp"

namespace aesim {

// What each pixel is made of, drawn from its own seeded streams so that a pixel's threshold and
// starting charge depend only on (sim.seed, pixel index), never on simulation order or fidelity.
IntegrateFire::Sensor pixel_sensor(const PixelParams& pixel);
double pixel_threshold(const PixelParams& pixel, std::uint64_t seed, std::uint64_t pixel_index);
double initial_fraction(const PixelParams& pixel, std::uint64_t seed, std::uint64_t pixel_index);
SplitMix64 shot_noise_stream(std::uint64_t seed, std::uint64_t pixel_index);

}  // namespace aesim
