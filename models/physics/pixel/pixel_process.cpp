#include "aesim/pixel/pixel_process.hpp"

#include "aesim/pixel/pixel_draws.hpp"

namespace aesim {

PixelProcess::PixelProcess(const sc_core::sc_module_name& name, const PixelParams& pixel, const SimParams& sim,
                           const Photocurrents& photocurrents, std::size_t index, const AddressEvent& identity)
    : sc_module(name),
      photocurrents_(photocurrents),
      index_(index),
      identity_(identity),
      t_end_(sim.duration),
      noise_{shot_noise_stream(sim.seed, index), pixel_threshold(pixel, sim.seed, index)},
      sensor_(pixel_sensor(pixel)),
      core_(sensor_, noise_.threshold, 0.0, photocurrents.current(0, index), initial_fraction(pixel, sim.seed, index),
            noise_.rng),
      next_boundary_(photocurrents.next_change(0, index)) {
  SC_METHOD(step);
}

void PixelProcess::step() {
  if (!started_) {
    started_ = true;
  } else if (pending_fire_) {
    AddressEvent e = identity_;
    e.t = core_.next_fire();
    bus->request(e);
    core_.fire(sensor_, noise_);
  } else {
    core_.set_current(sensor_, photocurrents_.boundary_time(next_boundary_),
                      photocurrents_.current(next_boundary_, index_));
    next_boundary_ = photocurrents_.next_change(next_boundary_, index_);
  }
  schedule();
}

void PixelProcess::schedule() {
  const double t_fire = core_.next_fire();
  const double t_boundary =
      next_boundary_ == Photocurrents::kNoChange ? kNever : photocurrents_.boundary_time(next_boundary_);
  pending_fire_ = fires_first(t_fire, t_boundary);
  const double t_next = pending_fire_ ? t_fire : t_boundary;
  if (!(t_next <= t_end_)) return;  // nothing more happens to this pixel within the run
  next_trigger(sc_core::sc_time(t_next, sc_core::SC_SEC) - sc_core::sc_time_stamp());
}

}  // namespace aesim
