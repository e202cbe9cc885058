#pragma once
#include <cstdint>
#include <systemc>

#include "aesim/bus/pixel_bus_if.hpp"
#include "aesim/pixel/integrate_fire.hpp"
#include "aesim/scene/photocurrents.hpp"

namespace aesim {

// An integrate-and-fire pixel as a SystemC module (sim.fidelity=pixel_processes). It wakes only when something happens to it:
// its next firing (computed in closed form by IntegrateFire) or a frame boundary where its own
// light changes. A dark pixel of a still scene never wakes at all.
class PixelProcess : public sc_core::sc_module {
 public:
  sc_core::sc_port<PixelBusIf> bus;

  PixelProcess(const sc_core::sc_module_name& name, const PixelParams& pixel, const SimParams& sim,
               const Photocurrents& photocurrents, std::size_t index, const AddressEvent& identity);
  SC_HAS_PROCESS(PixelProcess);

 private:
  void step();
  void schedule();

  const Photocurrents& photocurrents_;
  std::size_t index_;
  AddressEvent identity_;
  double t_end_;
  IntegrateFire::ShotNoise noise_;
  IntegrateFire::Sensor sensor_;
  IntegrateFire core_;
  std::uint64_t next_boundary_;
  bool started_ = false;
  bool pending_fire_ = false;
};

}  // namespace aesim
