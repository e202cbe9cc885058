#pragma once
#include <cstdint>
#include <vector>

#include "events/address_event.hpp"

namespace aesim {

// What became of a fired event.
enum class Fate : std::uint8_t {
  Delivered,  // reached the receiver output intact
  Collided,   // lost in a collision the receiver detected and discarded
  Absorbed,   // fired while Ack was high (cycle fidelity): withdrawn before the receiver could see it;
              // a collision with the transaction in progress, counted and written as "collided"
  Ghost,      // lost in a collision the receiver did not detect: it output the OR of the addresses
  Dropped,    // lost for another reason (receiver FIFO full)
  Pending,    // still waiting for the bus when the run ended (arbitrated bus past saturation)
};
const char* to_string(Fate fate);

// Ground truth for one fired event (--truth).
struct TruthRecord {
  AddressEvent firing;  // firing.t is the fire time
  Fate fate = Fate::Delivered;
  double t_deliver = 0;  // when the receiver took it (Delivered only)
};

// Counters of SPEC section 5, per tile. `collided` counts fired events lost to collisions,
// whether detected (Fate::Collided, Fate::Absorbed) or not (Fate::Ghost); `ghost` counts the wrong events the
// receiver output for undetected collisions; `delivered` counts every output event, ghosts too.
struct TileCounters {
  std::uint64_t fired = 0, delivered = 0, collided = 0, ghost = 0, dropped = 0, pending = 0;
  // The fraction of fired events lost to collisions (0 when none fired).
  double collision_fraction() const {
    return fired ? static_cast<double>(collided) / static_cast<double>(fired) : 0.0;
  }
};

struct LatencyStats {
  double mean = 0, p99 = 0, max = 0;  // s, fire to delivery, over delivered events
};

// The record of a run, filled in by the bus models (fates) and the receivers (output). Each
// tile's records are kept apart, so tiles may be simulated on separate threads (one thread per
// tile at a time), and merged in time order by finish().
class EventLog {
 public:
  EventLog(int tiles, bool keep_truth);

  // Counts firings per pixel (y * cols + x) in all and within [0, window]: the sizing metrics.
  // Tiles on separate threads touch separate pixels.
  void count_pixels(std::size_t pixels, std::uint32_t cols, double window) {
    fired_per_pixel_.assign(pixels, 0);
    window_per_pixel_.assign(pixels, 0);
    cols_ = cols;
    window_ = window;
  }
  void fired(const AddressEvent& firing) {
    Tile& tile = tiles_[firing.tile];
    ++tile.counters.fired;
    tile.address_ones += static_cast<std::uint64_t>(__builtin_popcount(firing.bus_address));
    if (!fired_per_pixel_.empty()) {
      const std::size_t i = std::size_t(firing.y) * cols_ + firing.x;
      ++fired_per_pixel_[i];
      if (firing.t <= window_) ++window_per_pixel_[i];
    }
  }
  const std::vector<std::uint32_t>& fired_per_pixel() const { return fired_per_pixel_; }
  const std::vector<std::uint32_t>& window_per_pixel() const { return window_per_pixel_; }
  // 1 bits of the addresses of every fired event: what the bus lines carried.
  std::uint64_t address_ones() const;
  // Every fired event is resolved exactly once, when its fate is known.
  void resolve(const AddressEvent& firing, Fate fate, double t_deliver = 0);
  // The receiver's output: a delivered event, or a ghost (flags & kGhostEvent).
  void output(const AddressEvent& e);
  // Merges the tiles: outputs by (time, tile, address), truth by (fire time, tile, address), so
  // files do not depend on the order in which simultaneous processes or threads ran.
  void finish();

  const std::vector<AddressEvent>& events() const { return events_; }
  const std::vector<TruthRecord>& truth() const { return truth_; }
  std::vector<TileCounters> tiles() const;
  TileCounters totals() const;
  LatencyStats latency() const;

 private:
  struct Tile {
    TileCounters counters;
    std::vector<AddressEvent> events;
    std::vector<TruthRecord> truth;
    std::vector<double> latencies;  // waits longer than zero
    std::uint64_t zero_latencies = 0;
    std::uint64_t address_ones = 0;
  };
  std::vector<Tile> tiles_;
  std::vector<AddressEvent> events_;
  std::vector<TruthRecord> truth_;
  std::vector<double> latencies_;
  std::uint64_t zero_latencies_ = 0;
  bool keep_truth_;
  std::vector<std::uint32_t> fired_per_pixel_, window_per_pixel_;
  std::uint32_t cols_ = 0;
  double window_ = 0;
};

}  // namespace aesim
