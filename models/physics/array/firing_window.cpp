#include "aesim/array/firing_window.hpp"

#include <stdexcept>

namespace aesim {

FiringWindow::Writer FiringWindow::start(double from, double to, std::size_t expected, std::size_t room) {
  // Two buckets a firing: with one, a uniform scene's pixels shared buckets so often that the
  // insertion pass after the counting sort took a third of the sort (bright QCIF, summary only:
  // 116 -> 131 M events/s with two; four gained nothing more).
  std::size_t buckets = 16;
  while (buckets < 2 * expected && buckets < (std::size_t(1) << 20)) buckets *= 2;
  const double width = (to - from) / static_cast<double>(buckets);
  per_width_ = width > 0 ? 1.0 / width : 0.0;
  last_bucket_ = static_cast<double>(buckets - 1);
  count_.assign(buckets, 0);
  if (added_.size() < room) added_.resize(room);
  added_count_ = 0;
  Writer w;
  w.out_ = added_.data();
  w.n_ = 0;
  w.room_ = room;
  w.count_ = count_.data();
  w.from_ = from;
  w.per_width_ = per_width_;
  w.last_bucket_ = last_bucket_;
  w.overflow_ = false;
  return w;
}

void FiringWindow::finish(const Writer& writer) {
  if (writer.overflow_) throw std::logic_error("a window of firings outgrew the room made for it");
  added_count_ = writer.n_;
  sort();
}

void FiringWindow::sort() {
  // Where each bucket starts in the sorted order.
  std::uint32_t at = 0;
  for (std::uint32_t& c : count_) {
    const std::uint32_t n = c;
    c = at;
    at += n;
  }
  if (sorted_.size() < added_count_) sorted_.resize(added_.size());
  Firing* const sorted = sorted_.data();
  std::uint32_t* const start = count_.data();
  const Firing* const added = added_.data();
  for (std::size_t i = 0; i < added_count_; ++i) sorted[start[added[i].bucket]++] = added[i];
  // Buckets follow time, so what is left is within a bucket (a few firings): an insertion sort,
  // which moves nothing past an equal time, so equal times keep the bus-address order they came in.
  for (std::size_t i = 1; i < added_count_; ++i) {
    if (!(sorted[i].t < sorted[i - 1].t)) continue;
    const Firing f = sorted[i];
    std::size_t j = i;
    for (; j > 0 && f.t < sorted[j - 1].t; --j) sorted[j] = sorted[j - 1];
    sorted[j] = f;
  }
}

namespace {
thread_local std::unique_ptr<FiringWindow> spare;
}  // namespace

std::unique_ptr<FiringWindow> FiringWindow::take() {
  if (spare) return std::move(spare);
  return std::make_unique<FiringWindow>();
}

void FiringWindow::give_back(std::unique_ptr<FiringWindow> window) {
  if (!spare) spare = std::move(window);
}

}  // namespace aesim
