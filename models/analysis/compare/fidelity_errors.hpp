#pragma once
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

}  // namespace aesim
