#pragma once
#include <cstdint>
#include <vector>

#include "aesim/containers/min_heap.hpp"

namespace aesim {

// A tile's pixels ordered by their next wake-up (a firing or a change of light): a calendar queue.
// Time is cut into buckets of equal width; a "year" of N buckets ahead of the present holds every
// wake-up due within it, each bucket an unsorted list threaded through the pixels, and a bucket is
// sorted only when it becomes the present, which costs little at the few entries a bucket holds.
// Wake-ups beyond the year (dim pixels, pixels waiting for light) wait in a heap and join the
// buckets as the year moves on, so they never crowd the hot buckets. Pushing and popping cost
// O(1) for the bright pixels that make most events, against O(log n) for a heap.
//
// Entries come out in exactly the order of (time, key), as from a heap: buckets follow time
// (floor(t / width) never decreases as t grows) and the present bucket is sorted by both.
//
// A pixel waiting in a bucket costs 8 bytes: its key and the next pixel of the bucket. Its time is
// not stored twice: the owner's `time_of(slot)` gives it back when the bucket becomes the present
// (it must return exactly the time pushed; the pixel's record is read then, just before it fires).
class WakeCalendar {
 public:
  struct Entry {
    double t;
    std::uint32_t key;   // orders simultaneous wake-ups (the bus address)
    std::uint32_t slot;  // the pixel
  };

  // For `slots` pixels; `horizon` (s) is the year: wake-ups further ahead go to the heap. Buckets
  // are a power of two near the number of pixels, so a year of pixels firing once each fills each
  // bucket about once.
  WakeCalendar(std::size_t slots, double horizon);

  void push(std::uint32_t slot, double t, std::uint32_t key) {
    const std::int64_t bucket = bucket_of(t);
    if (bucket > now_ && bucket - now_ <= static_cast<std::int64_t>(mask_)) {
      into_year({t, key, slot}, bucket);
    } else {
      push_outside_year({t, key, slot}, bucket);
    }
  }
  // The earliest entry, or false when none is left.
  template <typename TimeOf>
  bool peek(Entry& e, const TimeOf& time_of) {
    if (present_.empty() && !advance(time_of)) return false;
    e = present_.back();
    return true;
  }
  // Removes the entry peek() gave.
  void pop() { present_.pop_back(); }
  // The entry after the one peek() gave, when the present bucket holds it (for prefetching).
  const Entry* following() const { return present_.size() >= 2 ? &present_[present_.size() - 2] : nullptr; }

 private:
  struct Before {
    bool operator()(const Entry& a, const Entry& b) const { return (a.t < b.t) | ((a.t == b.t) & (a.key < b.key)); }
  };
  // Wake-up times are never negative, so truncation is the floor (std::floor is a library call on
  // a baseline x86-64, and this runs twice an event).
  std::int64_t bucket_of(double t) const {
    const double b = t * per_width_;
    return b < kLastBucket ? static_cast<std::int64_t>(b) : static_cast<std::int64_t>(kLastBucket);
  }
  void into_year(const Entry& e, std::int64_t bucket) {
    std::uint32_t& head = head_[static_cast<std::uint64_t>(bucket) & mask_];
    nodes_[e.slot] = Node{e.key, head};
    head = e.slot;
    ++in_year_;
  }
  void push_outside_year(const Entry& e, std::int64_t bucket);
  // Moves to the next bucket that holds anything; false when none is left.
  template <typename TimeOf>
  bool advance(const TimeOf& time_of) {
    while (present_.empty()) {
      if (!next_bucket()) return false;
      std::uint32_t& head = head_[static_cast<std::uint64_t>(now_) & mask_];
      // Field by field: an Entry built on the stack and copied whole stalled on store forwarding
      // (two 8-byte stores read back as one 16-byte load).
      for (std::uint32_t s = head; s != kNone;) {
        const Node& node = nodes_[s];
        Entry& e = present_.emplace_back();
        e.t = time_of(s);
        e.key = node.key;
        e.slot = s;
        s = node.next;
      }
      head = kNone;
      in_year_ -= present_.size();
      sort_present();
    }
    return true;
  }
  // Steps the present to the next bucket (jumping to the far heap's first when the year is
  // empty), bringing what the far heap holds inside the new year into the buckets. Inline for
  // the common step, one bucket on with nothing due from the far heap.
  bool next_bucket() {
    if (in_year_ == 0 || (!far_.empty() && bucket_of(far_.top().t) - (now_ + 1) <= static_cast<std::int64_t>(mask_))) {
      return next_bucket_far();
    }
    ++now_;
    // The next bucket's first pixel is the next list to walk.
    const std::uint32_t coming = head_[static_cast<std::uint64_t>(now_ + 1) & mask_];
    if (coming != kNone) __builtin_prefetch(&nodes_[coming]);
    return true;
  }
  bool next_bucket_far();
  // Latest first, so the earliest pops from the back. A bucket holds a pixel or two, where an
  // insertion sort in place, inline, beats a call and std::sort's.
  void sort_present() {
    if (present_.size() > 16) return sort_large_present();
    for (std::size_t i = 1; i < present_.size(); ++i) {
      const Entry e = present_[i];
      std::size_t j = i;
      for (; j > 0 && Before()(present_[j - 1], e); --j) present_[j] = present_[j - 1];
      present_[j] = e;
    }
  }
  void sort_large_present();

  // Bucket numbers stay far below overflow whatever the times (a run is at most 1e6 s long).
  static constexpr double kLastBucket = 4.0e18;

  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  // A pixel while it sits in a bucket: its key and the next pixel of the bucket.
  struct Node {
    std::uint32_t key;
    std::uint32_t next;
  };
  std::vector<std::uint32_t> head_;  // per bucket: its first pixel
  std::vector<Node> nodes_;          // per pixel
  std::uint64_t mask_;
  double per_width_;             // 1 / bucket width
  std::int64_t now_ = -1;        // the present bucket
  std::size_t in_year_ = 0;      // entries in the buckets
  std::vector<Entry> present_;   // the present bucket, sorted latest first
  MinHeap<Entry, Before, 4> far_; // beyond the year
};

}  // namespace aesim
