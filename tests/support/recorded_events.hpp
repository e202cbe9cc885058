#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
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

// One number's bytes, little-endian.
template <typename T>
std::string little(T v) {
  LittleEndianBytes b;
  b.put(v);
  return b.bytes;
}

// A camera's CD event as a reader should give it back.
struct Cd {
  std::int64_t t_us;
  std::uint32_t x, y;
  bool on;
};

// A camera's EVT 3.0 words as a driver publishes them in packets, cut wherever a packet filled:
// here between a vector's base and the vector (`first_cut`), and inside a word (`second_cut`).
// Read as one stream, as the camera wrote it, they are `events` on an array of 40x8.
struct CutEvt3Words {
  std::string words;
  std::size_t first_cut = 0, second_cut = 0;
  std::vector<Cd> events;
};
inline CutEvt3Words cut_evt3_words() {
  LittleEndianBytes w;
  const auto word = [&](unsigned type, unsigned v) { w.put<std::uint16_t>(static_cast<std::uint16_t>((type << 12) | v)); };
  CutEvt3Words c;
  word(0x8, 0x005);            // EVT_TIME_HIGH
  word(0x6, 0x010);            // EVT_TIME_LOW: t = 5 * 4096 + 16
  word(0x0, 3);                // EVT_ADDR_Y: row 3
  word(0x2, (1u << 11) | 7);   // EVT_ADDR_X: (7, 3) ON
  word(0x3, 16);               // VECT_BASE_X: column 16, OFF
  c.first_cut = w.bytes.size();
  word(0x5, 0x81);             // VECT_8: columns 16 and 23
  word(0x6, 0x020);            // EVT_TIME_LOW: t = 5 * 4096 + 32
  word(0x2, (1u << 11) | 39);  // (39, 3) ON
  c.second_cut = c.first_cut + 3;  // inside the time-low word after the vector
  c.words = w.bytes;
  const std::int64_t t0 = 5 * 4096 + 16, t1 = 5 * 4096 + 32;
  c.events = {{t0, 7, 3, true}, {t0, 16, 3, false}, {t0, 23, 3, false}, {t1, 39, 3, true}};
  return c;
}

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

// That reading (`read()`) is refused with a one-line InputError saying `words`.
template <typename Read>
void expect_refused_saying(Read read, const std::string& words) {
  try {
    read();
    ADD_FAILURE() << "accepted: " << words;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

// Whether the reader's account of what it left out says `words`.
inline bool noted(const EventRecording& rec, const std::string& words) {
  return std::any_of(rec.skipped.begin(), rec.skipped.end(), [&](const std::string& s) { return s.find(words) != std::string::npos; });
}

}  // namespace aesim::testing
