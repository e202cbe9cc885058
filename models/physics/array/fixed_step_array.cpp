#include "aesim/array/fixed_step_array.hpp"

#include <cmath>

#include "aesim/pixel/pixel_draws.hpp"

namespace aesim {

FixedStepArray::FixedStepArray(const sc_core::sc_module_name& name, const PixelParams& pixel, const SimParams& sim,
                               const Photocurrents& photocurrents, const AddressMap& map, std::vector<EventBus*> buses)
    : sc_module(name),
      photocurrents_(photocurrents),
      buses_(std::move(buses)),
      step_(sim.step),
      t_end_(sim.duration),
      reset_steps_(static_cast<std::uint32_t>(std::ceil(pixel.t_reset / sim.step - 1e-9))),
      next_boundary_(photocurrents.frames() > 1 ? 1 : Photocurrents::kNoChange) {
  const std::size_t n = photocurrents.pixels();
  charge_.resize(n);
  threshold_.resize(n);
  current_.resize(n);
  resetting_.assign(n, 0);
  identity_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    threshold_[i] = pixel_threshold(pixel, sim.seed, i);
    charge_[i] = initial_fraction(pixel, sim.seed, i) * threshold_[i];
    current_[i] = photocurrents.current(0, i);
    identity_[i] = map.event_at({static_cast<std::uint32_t>(i % static_cast<std::size_t>(map.cols())),
                                 static_cast<std::uint32_t>(i / static_cast<std::size_t>(map.cols()))});
  }
  SC_METHOD(tick);
  sensitive << tick_event_;
  dont_initialize();
  tick_event_.notify(sc_core::sc_time(step_, sc_core::SC_SEC));
}

void FixedStepArray::tick() {
  ++steps_;
  const double now = static_cast<double>(steps_) * step_;
  // The light of the step that just ended: frames change only at tick granularity here.
  while (next_boundary_ != Photocurrents::kNoChange && photocurrents_.boundary_time(next_boundary_) < now) {
    frame_ = next_boundary_;
    ++next_boundary_;
    for (std::size_t i = 0; i < current_.size(); ++i) current_[i] = photocurrents_.current(frame_, i);
  }
  for (std::size_t i = 0; i < charge_.size(); ++i) {
    if (resetting_[i] > 0) {
      --resetting_[i];
      continue;
    }
    charge_[i] += current_[i] * step_;
    if (charge_[i] < threshold_[i]) continue;
    const double crossed = std::floor(charge_[i] / threshold_[i]);
    if (crossed > 1) ++multi_fire_steps_;
    // Without reset time the charge of every crossing is spent and the rest kept, so counts stay
    // right; with it, a firing starts a reset of whole steps and the rest of the step is lost.
    const double fires = reset_steps_ > 0 ? 1.0 : crossed;
    charge_[i] = reset_steps_ > 0 ? 0.0 : charge_[i] - fires * threshold_[i];
    if (reset_steps_ > 0) resetting_[i] = reset_steps_;
    AddressEvent e = identity_[i];
    e.t = now;
    for (double k = 0; k < fires; ++k) buses_[e.tile]->request(e);
  }
  if (static_cast<double>(steps_ + 1) * step_ <= t_end_ * (1 + 1e-12)) {
    tick_event_.notify(sc_core::sc_time(static_cast<double>(steps_ + 1) * step_, sc_core::SC_SEC) -
                       sc_core::sc_time_stamp());
  }
}

}  // namespace aesim
