#pragma once
#include <cstdint>
#include <vector>

#include "aesim/array/queue_model.hpp"
#include "aesim/emulator/behaviours.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

// The source paper's frame-to-events emulator (aesim emulate).
//
// For each frame, at the imager's resolution (area resampling) and after grey-level clipping, the
// behaviour gives a map P (0..1 of full scale 255). The frame's events follow eq. 1 and eq. 3
// (f_max: events per frame of a full-scale pixel), by `spread` (queue_model.hpp): Even (default),
// pixel i enters round(f_max * P_i) times, spread evenly through the frame's passes; Literal, eq. 3
// as written, N = round(f_max * P_max) passes and an entry at pass n when
// n mod round(P_max / P_i) == 0. Pixels are scanned in raster order within a pass; P_i = 0 never
// enters. `centroid` instead gives one event per frame at the rounded centroid of
// the thresholded motion image. `motion` and `centroid` need a previous frame, so the first frame
// gives none.
//
// Bus contention in the emulator: after each event a random event (a uniformly drawn pixel)
// enters with probability chaos_in, and each event of the queue leaves it with probability
// chaos_out (both seeded). Event j of the M events of frame k gets the synthetic time
// (k + (j + 1/2) / M) / frame_rate.
struct EmulatorSettings {
  Behaviour behaviour = Behaviour::Intensity;
  double threshold = 0;      // 0..1 of full scale
  double clip_low = 0;       // 0..1
  double clip_high = 1;      // 0..1
  int width = 0, height = 0; // imager resolution (0: the input's)
  double f_max = 20;         // events per frame of a full-scale pixel
  double frame_rate = 25;    // Hz, for the synthetic timestamps
  double chaos_in = 0, chaos_out = 0;
  std::uint64_t seed = 1;
  double max_events = 1e8;   // the work limit (--max-events), charged frame by frame before the work
  QueueSpread spread = QueueSpread::Even;
};

struct EmulatedEvent {
  double t;
  std::uint32_t x, y;
  std::uint32_t frame;
};

std::vector<EmulatedEvent> emulate(const std::vector<Image>& frames, const EmulatorSettings& settings);

}  // namespace aesim
