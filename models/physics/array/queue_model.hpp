#pragma once
#include <cstdint>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// sim.fidelity=queue: the source paper's event-queue model, no pixel physics and no timing.
// Per frame (a still scene is one frame lasting sim.duration; a sequence, its frames), with P_i
// the scene value of pixel i, recovered from its photocurrent as (I - i_dark) / i_max, and P_max
// the frame's largest:
//   eq. 1: pixel i fires f_i = f_max * P_i times per second at full scale f_max = i_max/(c_int*dv_int);
//   eq. 3: the frame is N = round(f_max * P_max * T_frame) iterations n = 1..N; pixel i enters the
//          queue at iteration n when n mod round(P_max / P_i) == 0, pixels in raster order within an
//          iteration; P_i = 0 never enters.
// The queue's events get synthetic times spread evenly over the frame (event j of M at
// frame_start + (j + 1/2) T_frame / M), so buses see them in queue order. Dark current, reset
// time, mismatch and shot noise do not exist in this model.
// Frames with light whose brightest pixel should fire less than half a time within the frame
// round to zero iterations: the model then emits nothing for them. They are counted in
// `empty_lit_frames` (when given) so that the run can say so instead of failing silently.
std::vector<AddressEvent> queue_events(const PixelParams& pixel, const SimParams& sim,
                                       const Photocurrents& photocurrents, const AddressMap& map,
                                       std::uint64_t* empty_lit_frames = nullptr);

// The work queues may take over a run: entries (events) and pixel visits (iterations x pixels),
// counted before each frame's queue is built; exceeding either is an InputError naming `limit`.
struct QueueBudget {
  double max_entries = 1e8, max_visits = 1e10;
  const char* limit = "sim.max_events";
  double entries = 0, visits = 0;
};

// The synthetic time of entry j of a queue of m entries in the frame [start, start + length): the
// entries split the frame evenly, each at the middle of its share, (j + 1/2) / m of the way.
inline double queue_entry_time(double start, double length, std::size_t j, std::size_t m) {
  return start + (static_cast<double>(j) + 0.5) * (length / static_cast<double>(m));
}

// How a frame's passes place each pixel's entries.
//  - Literal: eq. 3 as the paper writes it: N = round(f_max * P_max * T) passes, pixel i enters at
//    pass n when n mod round(P_max / P_i) == 0, so its count can only be N / k for a whole k (a
//    grey level 170 of 255 enters 10 times in 20 passes, 171 enters 20; eq. 1 says 13.3 for both).
//  - Even: eq. 1's count, rounded once, c_i = round(f_max * P_i * T), spread evenly through
//    N = max c_i passes in the spirit of eq. 3: pixel i enters at pass n when floor(n c_i / N)
//    steps, which is eq. 3's pattern whenever N / c_i is whole.
// Within a pass, pixels enter in raster order.
enum class QueueSpread { Literal, Even };

// One frame's queue as pixel indices (y * width + x) in queue order, on normalised values.
// With a budget, the frame's work is charged to it first.
std::vector<std::uint32_t> queue_order(const std::vector<double>& values, double full_scale_rate, double frame_time,
                                       QueueBudget* budget = nullptr, QueueSpread spread = QueueSpread::Literal);

}  // namespace aesim
