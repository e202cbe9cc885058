#include "aesim/pixel/integrate_fire.hpp"

#include <algorithm>

namespace aesim {
namespace {

double draw_target(const IntegrateFire::Sensor& s, double threshold, SplitMix64& rng) {
  if (!s.shot_noise) return threshold;
  return kElectronCharge * GammaDraw(threshold / kElectronCharge)(rng);
}

}  // namespace

IntegrateFire::IntegrateFire(const Sensor& sensor, double threshold, double t0, double current,
                             double initial_fraction, SplitMix64& rng)
    : target_(draw_target(sensor, threshold, rng)), current_(current), anchor_t_(t0) {
  anchor_q_ = std::clamp(initial_fraction, 0.0, 1.0) * target_;
  anchored(sensor);
}

double IntegrateFire::reset_end_of_last_cycle(const Sensor& sensor) const {
  // Only meaningful when cycles_ > 0: the previous firing's time plus the reset.
  return first_ + static_cast<double>(cycles_ - 1) * period_ + sensor.t_reset;
}

void IntegrateFire::start_new_integration(const Sensor& sensor, ShotNoise& noise) {
  anchor_t_ = next_fire() + sensor.t_reset;
  anchor_q_ = 0;
  cycles_ = 0;
  // Without shot noise every target is the threshold, the one the pixel was made with.
  if (sensor.shot_noise) target_ = noise.next_target();
}

double IntegrateFire::charge_at(const Sensor& sensor, double t) const {
  double start = anchor_t_;
  double q0 = anchor_q_;
  if (cycles_ > 0) {
    start = reset_end_of_last_cycle(sensor);
    q0 = 0;
  }
  if (t <= start || !(current_ > 0)) return q0;
  return std::min(target_, q0 + current_ * (t - start));
}

void IntegrateFire::set_current(const Sensor& sensor, double t, double current) {
  const double q = charge_at(sensor, t);
  const double resume = cycles_ > 0 ? reset_end_of_last_cycle(sensor) : anchor_t_;
  // In reset (t before the integration resumes) the new anchor is the end of the reset.
  anchor_t_ = std::max(t, resume);
  anchor_q_ = q;
  cycles_ = 0;
  current_ = current;
  anchored(sensor);
}

}  // namespace aesim
