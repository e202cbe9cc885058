#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/event_files/event_file.hpp"

namespace aesim::testing {

// A file's bytes built little-endian, number by number, as a recorder lays them out.
struct LittleEndianBytes {
  std::string bytes;
  template <typename T>
  void put(T v) {
    for (std::size_t b = 0; b < sizeof(T); ++b) bytes += static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * b)) & 0xFF);
  }
};

// A camera's CD event as a reader should give it back.
struct Cd {
  std::int64_t t_us;
  std::uint32_t x, y;
  bool on;
};

inline void expect_events(const EventRecording& rec, const std::vector<Cd>& expected) {
  ASSERT_EQ(rec.events.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    // Whole microseconds, exactly: a stamp since the epoch (a ROS bag's) is 1.5e15 us, where four
    // units in the last place of its double seconds are a microsecond.
    EXPECT_EQ(std::llround(rec.events[i].t * 1e6), expected[i].t_us);
    EXPECT_EQ(rec.events[i].x, expected[i].x);
    EXPECT_EQ(rec.events[i].y, expected[i].y);
    EXPECT_EQ(rec.events[i].flags, expected[i].on ? kNormalEvent : kOffEvent);
  }
}

// Whether the reader's account of what it left out says `words`.
inline bool noted(const EventRecording& rec, const std::string& words) {
  return std::any_of(rec.skipped.begin(), rec.skipped.end(), [&](const std::string& s) { return s.find(words) != std::string::npos; });
}

}  // namespace aesim::testing
