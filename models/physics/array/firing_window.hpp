#pragma once
#include <cstdint>
#include <memory>
#include <vector>

namespace aesim {

// One time window's firings of a tile whose pixels all fire periodically (light that never
// changes, no shot noise), put in (time, bus address) order by a counting sort: the tile hands in
// each pixel's firings in the window pixel by pixel, in bus-address order, and the sort keeps that
// order among equal times. Where a calendar queue pops and pushes every firing through a list, this
// writes each once, counts it into a bucket of time, and reads it back in order: much less work
// when nearly every pixel fires in every window.
class FiringWindow {
 public:
  struct Firing {
    double t;
    std::uint32_t key;     // bus address
    std::uint32_t bucket;  // of time within the window, kept for the sort
  };

  // Where a window's firings are written as they come: plain locals, so that the hot loop keeps
  // them in registers (a call in it, even one never taken, made GCC keep the loop's doubles on
  // the stack). Room for them is made before: see start().
  class Writer {
   public:
    // A firing not `kept` is written in the next free place and left there to be overwritten:
    // a caller that cannot predict whether it falls in the window passes it without a branch.
    void add(double t, std::uint32_t key, bool kept = true) {
      if (n_ == room_) {
        overflow_ = overflow_ || kept;
        return;
      }
      // Times in the window are never before `from`, nor (kept ones) past `to`; the clamp keeps
      // `to` and any later time in the last bucket.
      double b = (t - from_) * per_width_;
      b = b < last_bucket_ ? b : last_bucket_;
      const auto bucket = static_cast<std::uint32_t>(b);
      out_[n_].t = t;
      out_[n_].key = key;
      out_[n_].bucket = bucket;
      n_ += kept;
      count_[bucket] += kept;
    }

   private:
    friend class FiringWindow;
    Firing* out_;
    std::size_t n_, room_;
    std::uint32_t* count_;
    double from_, per_width_, last_bucket_;
    bool overflow_;
  };

  // A window over [from, to] with about `expected` firings and room for `room`: add() them
  // through the writer, in the order described above, then finish().
  Writer start(double from, double to, std::size_t expected, std::size_t room);
  // Sorts what was written; first() .. end() is then the window in order. Throws std::logic_error
  // if more came than the room made for them (they were not written).
  void finish(const Writer& writer);
  const Firing* first() const { return sorted_.data(); }
  const Firing* end() const { return sorted_.data() + added_count_; }

  // A window's buffers are only needed until its firings are taken, so a thread keeps one spare
  // for the next tile it works on instead of every tile keeping its own.
  static std::unique_ptr<FiringWindow> take();
  static void give_back(std::unique_ptr<FiringWindow> window);

 private:
  void sort();

  double per_width_ = 0;
  double last_bucket_ = 0;
  std::vector<Firing> added_, sorted_;  // sized ahead; the first added_count_ are the window's
  std::size_t added_count_ = 0;
  std::vector<std::uint32_t> count_;
};

}  // namespace aesim
