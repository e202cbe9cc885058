#pragma once
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "aesim/events/event_log.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

// How far a run of some rung is from the event-rung reference of the same scene, sensor and seed.
struct FidelityErrors {
  double count_error = 0;               // sum over pixels of |n - n_ref|, over sum of n_ref
  double rms_time_error_s = 0;          // RMS difference of each pixel's k-th firings (paired)
  double collision_fraction = 0;        // of this run
  double collision_fraction_error = 0;  // |this - reference|
  double psnr_db = 0;                   // histogram reconstruction against the scene
};

// Both logs need their truth (every fired event). `scene` is the light the array saw, averaged
// over the run, at the array's size; reconstruction and scene are each normalised to their peak.
FidelityErrors fidelity_errors(const EventLog& reference, const EventLog& run, const Image& scene);

// PSNR (dB) of an image against a reference, both in [0, 1].
double psnr_db(const Image& image, const Image& reference);
// The same of pixels read through image(i) and reference(i), i < n: images that are not held as
// such (a large array's counts, normalised as they are read) need not be copied into one.
template <typename ImagePixel, typename ReferencePixel>
double psnr_db(std::size_t n, ImagePixel image, ReferencePixel reference) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = image(i) - reference(i);
    sum += d * d;
  }
  const double mse = sum / static_cast<double>(n);
  return mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

}  // namespace aesim
