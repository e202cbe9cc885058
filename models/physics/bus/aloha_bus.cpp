#include "aesim/bus/aloha_bus.hpp"

#include <algorithm>

namespace aesim {

void AlohaBus::request(const AddressEvent& firing) { request_all(&firing, 1); }

// Pixels firing within the same picosecond may arrive in either order: a firing is compared with
// the latest start of its cluster so far, so that order never matters. A firing is counted when
// its cluster closes, lone or not, so that the log reaches a pixel's counters once for both its
// firing and its delivery.
void AlohaBus::request_all(const AddressEvent* firings, std::size_t n) {
  if (n == 0) return;
  std::size_t i = 0;
  if (!cluster_.empty()) {
    for (; i < n && firings[i].t - latest_start_ < tau_; ++i) join(firings[i]);
    if (i == n) return;
    close_cluster();
  }
  // Clusters of this batch are [begin, j). Lone firings, most of them on a lightly loaded bus, go to
  // the log in runs, [singles, begin), before whatever collides after them.
  std::size_t begin = i, singles = i;
  double latest = firings[i].t;
  for (std::size_t j = i + 1; j < n; ++j) {
    if (firings[j].t - latest >= tau_) {
      if (j - begin > 1) {
        log_.fired_and_delivered(firings + singles, begin - singles);
        close_collision(firings + begin, j - begin);
        singles = j;
      }
      begin = j;
      latest = firings[j].t;
    } else {
      latest = std::max(latest, firings[j].t);
    }
  }
  log_.fired_and_delivered(firings + singles, begin - singles);
  // The last cluster waits for the next batch, which may still join it.
  for (std::size_t k = begin; k < n; ++k) join(firings[k]);
}

void AlohaBus::close_cluster() {
  if (cluster_.size() == 1) {
    log_.fired_and_delivered(cluster_.data(), 1);
  } else if (!cluster_.empty()) {
    close_collision(cluster_.data(), cluster_.size());
  }
  cluster_.clear();
}

void AlohaBus::close_collision(const AddressEvent* cluster, std::size_t n) {
  log_.fired_all(cluster, n);
  const Fate fate = detect_ ? Fate::Collided : Fate::Ghost;
  AddressEvent ghost = cluster[0];
  ghost.bus_address = 0;
  for (std::size_t i = 0; i < n; ++i) {
    log_.resolve(cluster[i], fate);
    ghost.t = std::min(ghost.t, cluster[i].t);
    ghost.bus_address |= cluster[i].bus_address;
  }
  if (!detect_) {
    const PixelAddress p = map_.locate(ghost.tile, ghost.bus_address);
    ghost.x = p.x;
    ghost.y = p.y;
    ghost.flags = kGhostEvent;
    log_.output(ghost);
  }
}

void ArbitratedBus::request(const AddressEvent& firing) { request_all(&firing, 1); }

void ArbitratedBus::request_all(const AddressEvent* firings, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const AddressEvent& firing = firings[i];
    log_.fired(firing);
    const double start = std::max(firing.t, free_at_);
    free_at_ = start + tau_;
    if (start > t_end_) {
      log_.resolve(firing, Fate::Pending);
      continue;
    }
    log_.resolve(firing, Fate::Delivered, start);
    AddressEvent delivered = firing;
    delivered.t = start;
    log_.output(delivered);
  }
}

}  // namespace aesim
