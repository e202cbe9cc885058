#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace aesim {

// A D-ary min-heap on `Before` (a strict weak order: before(a, b) means a comes out first), the one
// priority queue of the simulators' event loops. Its hot operation is replace_top(): the element
// just taken goes back with a later key, the pattern of "pop the earliest, reschedule it".
// replace_top() works bottom-up (walk the hole down along the smallest children to a leaf, then
// move the entry back up the little it needs), because a rescheduled entry usually lands behind
// most others; for D = 4 a full family is compared as a branch-free tournament. Callers whose
// comparisons are random should write `Before` with bitwise operators so the compiler selects with
// conditional moves.
template <class T, class Before, std::size_t D = 4>
class MinHeap {
  static_assert(D >= 2, "a heap needs at least two children per node");

 public:
  explicit MinHeap(Before before = Before()) : before_(before) {}

  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  const T& top() const { return items_.front(); }
  void reserve(std::size_t n) { items_.reserve(n); }

  // Builds the heap from `items` in O(n).
  void assign(std::vector<T> items) {
    items_ = std::move(items);
    for (std::size_t i = items_.size(); i-- > 0;) sift_down(i);
  }
  void push(const T& item) {
    items_.push_back(item);
    sift_up(items_.size() - 1, item);
  }
  void pop() {
    items_.front() = items_.back();
    items_.pop_back();
    if (!items_.empty()) sift_down(0);
  }
  // Replaces the top with `item` (which may order anywhere) and restores the heap.
  void replace_top(const T& item) {
    const std::size_t n = items_.size();
    T* h = items_.data();
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = D * i + 1;
      std::size_t best = first;
      if (D == 4 && first + 3 < n) {
        const std::size_t a = first + static_cast<std::size_t>(before_(h[first + 1], h[first]));
        const std::size_t b = first + 2 + static_cast<std::size_t>(before_(h[first + 3], h[first + 2]));
        best = before_(h[b], h[a]) ? b : a;
      } else {
        if (first >= n) break;
        const std::size_t last = std::min(first + D, n);
        for (std::size_t c = first + 1; c < last; ++c) {
          if (before_(h[c], h[best])) best = c;
        }
      }
      h[i] = h[best];
      i = best;
    }
    sift_up(i, item);
  }

 private:
  void sift_up(std::size_t i, const T& item) {
    while (i > 0) {
      const std::size_t parent = (i - 1) / D;
      if (!before_(item, items_[parent])) break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = item;
  }
  void sift_down(std::size_t i) {
    const std::size_t n = items_.size();
    const T moving = items_[i];
    for (;;) {
      const std::size_t first = D * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t last = std::min(first + D, n);
      for (std::size_t c = first + 1; c < last; ++c) {
        if (before_(items_[c], items_[best])) best = c;
      }
      if (!before_(items_[best], moving)) break;
      items_[i] = items_[best];
      i = best;
    }
    items_[i] = moving;
  }

  Before before_;
  std::vector<T> items_;
};

}  // namespace aesim
