#pragma once
#include <memory>
#include <vector>

#include <systemc>

#include "aesim/rungs/rung.hpp"
#include "aesim/tile/cycle_tile.hpp"

namespace aesim {

class ScheduleDriver;

// The array at the cycle fidelity: a CycleTile per tile (its wires, its bus and its receiver), fed
// by one process from the tiles' firing schedules. It lives in whatever SystemC context is current
// when it is built: the cycle rung's own, or the caller's (Imager). Everything `run` names must
// outlive it.
class CycleArray : public sc_core::sc_module {
 public:
  CycleArray(const sc_core::sc_module_name& name, const RungRun& run, const CycleOptions& options);
  ~CycleArray() override;
  const std::vector<std::unique_ptr<CycleTile>>& tiles() const { return tiles_; }
  // Whether the run is over: every firing handed to its bus and every tile quiescent.
  bool done() const;

 private:
  std::vector<std::unique_ptr<CycleTile>> tiles_;
  std::unique_ptr<ScheduleDriver> driver_;
};

// The request's options, with the RTL receiver when receiver.model asks for it and the request
// names no receiver of its own.
CycleOptions cycle_options(const RungRun& run);

}  // namespace aesim
