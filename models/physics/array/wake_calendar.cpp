#include "aesim/array/wake_calendar.hpp"

#include <algorithm>
#include <cmath>

namespace aesim {

WakeCalendar::WakeCalendar(std::size_t slots, double horizon)
    : nodes_(slots, Node{0, kNone}) {
  std::size_t buckets = 16;
  while (buckets < slots && buckets < (std::size_t(1) << 22)) buckets *= 2;
  head_.assign(buckets, kNone);
  mask_ = buckets - 1;
  const double width = horizon / static_cast<double>(buckets);
  per_width_ = std::isfinite(width) && width > 0 ? 1.0 / width : 1.0;
}

void WakeCalendar::push_outside_year(const Entry& e, std::int64_t bucket) {
  if (bucket <= now_) {
    // Due within the present bucket (a pixel brighter than a bucket is wide): in its sorted place.
    present_.insert(std::upper_bound(present_.begin(), present_.end(), e, [](const Entry& a, const Entry& b) {
                      return Before()(b, a);
                    }),
                    e);
  } else {
    far_.push(e);
  }
}

bool WakeCalendar::next_bucket_far() {
  if (in_year_ == 0) {
    if (far_.empty()) return false;
    // Nothing within the year: jump to the far heap's first.
    now_ = bucket_of(far_.top().t);
  } else {
    ++now_;
  }
  // The year moved on: what the far heap holds inside it joins the buckets.
  while (!far_.empty() && bucket_of(far_.top().t) - now_ <= static_cast<std::int64_t>(mask_)) {
    into_year(far_.top(), bucket_of(far_.top().t));
    far_.pop();
  }
  // The next bucket's first pixel is the next list to walk.
  const std::uint32_t coming = head_[static_cast<std::uint64_t>(now_ + 1) & mask_];
  if (coming != kNone) __builtin_prefetch(&nodes_[coming]);
  return true;
}

void WakeCalendar::sort_large_present() {
  std::sort(present_.begin(), present_.end(), [](const Entry& a, const Entry& b) { return Before()(b, a); });
}

}  // namespace aesim
