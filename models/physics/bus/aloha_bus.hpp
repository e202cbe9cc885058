#pragma once
#include <algorithm>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/bus/event_bus.hpp"
#include "aesim/events/event_log.hpp"

namespace aesim {

// bus.access=aloha at the event fidelity: textbook pure ALOHA. An event holds the bus for tau
// from its firing time t and is delivered (at t) iff no other event on this bus starts in
// (t - tau, t + tau). Events closer than tau chain into a cluster that is lost whole. With
// contention detection the receiver discards the cluster; without it, the receiver latches the
// bitwise OR of the cluster's addresses once, at the cluster's first start: one ghost event.
class AlohaBus final : public EventBus {
 public:
  AlohaBus(EventLog& log, const AddressMap& map, double tau, bool contention_detect)
      : log_(log), map_(map), tau_(tau), detect_(contention_detect) {}

  void request(const AddressEvent& firing) override;
  void request_all(const AddressEvent* firings, std::size_t n) override;
  void finish() override { close_cluster(); }
  double held_since() const override { return cluster_.empty() ? EventBus::held_since() : earliest_; }
  bool delivers_when_fired() const override { return true; }

 private:
  // The open cluster: the firings that may still collide with the next one. A batch's clusters
  // are found in place; only the last, which the next batch may extend, is copied here.
  void join(const AddressEvent& firing) {
    latest_start_ = cluster_.empty() ? firing.t : std::max(latest_start_, firing.t);
    earliest_ = cluster_.empty() ? firing.t : std::min(earliest_, firing.t);
    cluster_.push_back(firing);
  }
  void close_cluster();
  void close_collision(const AddressEvent* cluster, std::size_t n);

  EventLog& log_;
  const AddressMap& map_;
  double tau_;
  bool detect_;
  std::vector<AddressEvent> cluster_;
  double latest_start_ = 0;  // of the open cluster
  double earliest_ = 0;
};

// bus.access=arbitrated: events take the bus one after the other in fire order, each for tau;
// none is lost, each waits its turn. Delivery time is when its turn starts. Events whose turn
// would start after the end of the run are counted as pending, not delivered.
class ArbitratedBus final : public EventBus {
 public:
  ArbitratedBus(EventLog& log, double tau, double t_end)
      : log_(log), tau_(tau), t_end_(t_end) {}

  void request(const AddressEvent& firing) override;
  void request_all(const AddressEvent* firings, std::size_t n) override;

 private:
  EventLog& log_;
  double tau_;
  double t_end_;
  double free_at_ = 0;
};

}  // namespace aesim
