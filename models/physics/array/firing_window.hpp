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

  // Collects the firings over [from, to], about `expected` of them: `generate(add)` calls
  // add(t, key) for each, in the order described above; then sorts them, and first() .. end()
  // is the window in order.
  template <typename Generate>
  void make(double from, double to, std::size_t expected, Generate&& generate) {
    start(from, to, expected);
    // Locals, not members, while the firings come in: the loop's stores would make the compiler
    // reload members at every firing.
    Adder add{added_.data(), 0, added_.size(), count_.data(), from, per_width_, last_bucket_, this};
    generate(add);
    added_count_ = add.n;
    sort();
  }
  const Firing* first() const { return sorted_.data(); }
  const Firing* end() const { return sorted_.data() + added_count_; }

  // A window's buffers are only needed until its firings are taken, so a thread keeps one spare
  // for the next tile it works on instead of every tile keeping its own.
  static std::unique_ptr<FiringWindow> take();
  static void give_back(std::unique_ptr<FiringWindow> window);

 private:
  struct Adder {
    Firing* out;
    std::size_t n, capacity;
    std::uint32_t* count;
    double from, per_width, last_bucket;
    FiringWindow* window;
    void operator()(double t, std::uint32_t key) {
      if (n == capacity) grow();
      // Times in the window are never before `from`; the clamp keeps `to` in the last bucket.
      double b = (t - from) * per_width;
      b = b < last_bucket ? b : last_bucket;
      const auto bucket = static_cast<std::uint32_t>(b);
      out[n].t = t;
      out[n].key = key;
      out[n].bucket = bucket;
      ++n;
      ++count[bucket];
    }
    void grow() {
      window->added_.resize(2 * capacity);
      out = window->added_.data();
      capacity = window->added_.size();
    }
  };
  void start(double from, double to, std::size_t expected);
  void sort();

  double per_width_ = 0;
  double last_bucket_ = 0;
  std::vector<Firing> added_, sorted_;  // sized ahead; the first added_count_ are the window's
  std::size_t added_count_ = 0;
  std::vector<std::uint32_t> count_;
};

}  // namespace aesim
