#include "bus/aloha_bus.hpp"

#include <algorithm>

namespace aesim {

void AlohaBus::request(const AddressEvent& firing) { request_all(&firing, 1); }

void AlohaBus::request_all(const AddressEvent* firings, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const AddressEvent& firing = firings[i];
    log_.fired(firing);
    // Pixels firing within the same picosecond may arrive in either order; compare against the
    // latest start seen so that order never matters.
    if (!cluster_.empty() && firing.t - latest_start_ >= tau_) close_cluster();
    latest_start_ = cluster_.empty() ? firing.t : std::max(latest_start_, firing.t);
    earliest_ = cluster_.empty() ? firing.t : std::min(earliest_, firing.t);
    cluster_.push_back(firing);
  }
}

void AlohaBus::close_collision() {
  const Fate fate = detect_ ? Fate::Collided : Fate::Ghost;
  AddressEvent ghost = cluster_[0];
  ghost.bus_address = 0;
  for (const AddressEvent& e : cluster_) {
    log_.resolve(e, fate);
    ghost.t = std::min(ghost.t, e.t);
    ghost.bus_address |= e.bus_address;
  }
  if (!detect_) {
    const PixelAddress p = map_.locate(ghost.tile, ghost.bus_address);
    ghost.x = p.x;
    ghost.y = p.y;
    ghost.flags = kGhostEvent;
    log_.output(ghost);
  }
  cluster_.clear();
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
