#pragma once
#include <cstdint>

namespace aesim {

// One pixel's firings over a run, worked out by its tile's schedule rather than counted one by
// one (FiringSchedule::pixel_firings, EventLog::add_pixel_firings). Counts wrap at 2^32, as the
// log's per-pixel counters do.
struct PixelFirings {
  std::uint32_t index;   // the pixel, y * cols + x
  std::uint32_t all;     // firings within the run
  std::uint32_t within;  // of those, at or before the log's counting window
};

}  // namespace aesim
