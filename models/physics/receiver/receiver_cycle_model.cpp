#include "aesim/receiver/receiver_cycle_model.hpp"

#include <algorithm>

namespace aesim {
namespace {

std::uint64_t mask(int width) { return width >= 64 ? ~0ULL : (1ULL << width) - 1; }

}  // namespace

ReceiverCycleModel::ReceiverCycleModel(const Config& config)
    : config_(config),
      ts_mask_(mask(config.ts_width)),
      addr_mask_(static_cast<std::uint32_t>(mask(config.addr_width))),
      prescale_(std::max(1u, config.prescale)),
      limit_(std::min(config.fifo_limit, config.capacity)),
      ring_(std::max(1u, limit_)) {
  update_outputs();
}

void ReceiverCycleModel::reset() {
  s1_ = s2_ = s3_ = acking_ = false;
  divider_ = ts_ = 0;
  events_ = collisions_ = overflows_ = 0;
  head_ = count_ = 0;
  update_outputs();
}

void ReceiverCycleModel::clock(const Inputs& in) {
  // Values held before the edge.
  // Only the settled synchronizer stages decide; s1_ may be metastable in the circuit.
  const bool req_high = s2_ && s3_;
  const bool req_low = !s2_ && !s3_;
  // The stamp is the counter's value after this edge: the ticks completed by the latch edge.
  const bool tick_ends = divider_ + 1 >= prescale_;
  const std::uint64_t ts_next = tick_ends ? (ts_ + 1) & ts_mask_ : ts_;
  const std::uint64_t ts_now = config_.ts_external ? (in.ts & ts_mask_) : ts_next;
  const std::size_t count = count_;
  const bool full = count >= limit_;
  const bool pop = count > 0 && in.ready;
  const std::uint32_t addr = in.addr & addr_mask_;

  bool push = false;
  if (!acking_) {
    if (req_high) {
      if (in.contention && config_.discard_collisions) {
        ++collisions_;
        acking_ = true;
      } else if (full) {
        if (!config_.hold_when_full) {
          ++overflows_;
          collisions_ += in.contention ? 1 : 0;
          acking_ = true;
        }
      } else {
        push = true;
        ++events_;
        collisions_ += in.contention ? 1 : 0;
        acking_ = true;
      }
    }
  } else if (req_low) {
    acking_ = false;
  }

  if (pop) {
    head_ = head_ + 1 == ring_.size() ? 0 : head_ + 1;
    --count_;
  }
  if (push) {
    const std::size_t tail = (head_ + count_) % ring_.size();
    ring_[tail] = {ts_now, addr, in.contention};
    ++count_;
  }

  divider_ = tick_ends ? 0 : divider_ + 1;
  ts_ = ts_next;
  s3_ = s2_;
  s2_ = s1_;
  s1_ = in.req;
  events_ &= 0xFFFFFFFFULL;
  collisions_ &= 0xFFFFFFFFULL;
  overflows_ &= 0xFFFFFFFFULL;
  update_outputs();
}

}  // namespace aesim
