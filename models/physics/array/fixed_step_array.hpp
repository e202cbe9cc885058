#pragma once
#include <cstdint>
#include <systemc>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/bus/event_bus.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// sim.fidelity=fixed_step: the baseline a SystemC engineer would write first. A clock ticks every
// sim.step; at each tick every pixel adds I * step to its charge, and fires when the charge
// reaches its threshold; firings are stamped with the tick. Reset lasts whole steps
// (ceil(t_reset / step)). Its outcome past its validity is defined, not silent: a pixel whose
// charge crosses several thresholds in one step fires that many times (all stamped with the tick,
// the excess charge kept; with a reset time only once, the rest lost), and those steps are
// counted (multi_fire_steps) so the run warns that the step is coarser than the integration
// time. Shot noise is not modelled at this rung.
// Cost: pixels x steps, whatever the scene.
class FixedStepArray : public sc_core::sc_module {
 public:
  FixedStepArray(const sc_core::sc_module_name& name, const PixelParams& pixel, const SimParams& sim,
                 const Photocurrents& photocurrents, const AddressMap& map, std::vector<EventBus*> buses);
  SC_HAS_PROCESS(FixedStepArray);

  std::uint64_t multi_fire_steps() const { return multi_fire_steps_; }

 private:
  void tick();

  const Photocurrents& photocurrents_;
  std::vector<EventBus*> buses_;
  double step_, t_end_;
  std::uint32_t reset_steps_;
  std::uint64_t steps_ = 0;
  std::uint64_t frame_ = 0;
  std::uint64_t next_boundary_;  // the next frame change of the scene as a whole
  std::vector<double> charge_, threshold_, current_;
  std::vector<std::uint32_t> resetting_;
  std::vector<AddressEvent> identity_;
  std::uint64_t multi_fire_steps_ = 0;
  sc_core::sc_event tick_event_;
};

}  // namespace aesim
