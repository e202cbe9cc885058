#pragma once
#include <cstdint>
#include <vector>

namespace aesim {

// The least work an event-driven imager simulator can do per event, as a yardstick for the event
// rung measured in the same run: pop the earliest pixel from a calendar queue (a ring of buckets,
// each an intrusive unsorted list, no tie order), add its period, push it back, append an 8-byte
// record to a cache-resident buffer. No physics, no bus, no merge, no files. Returns the events made until
// `t_end` (s) from pixels of the given `periods` (s) starting at `phases` (s).
std::uint64_t ceiling_probe(const std::vector<double>& periods, const std::vector<double>& phases, double t_end);

}  // namespace aesim
