#pragma once
#include <memory>
#include <systemc>
#include <vector>

#include "array/address_map.hpp"
#include "bus/pixel_bus_if.hpp"
#include "pixel/pixel.hpp"
#include "receiver/event_log.hpp"

namespace aesim {

// The pixel array split into tiles, each tile with its own bus. The bus model is chosen by
// bus.access; every pixel of a tile is bound to that tile's bus.
class Imager : public sc_core::sc_module {
 public:
  Imager(const sc_core::sc_module_name& name, const SensorConfig& config, const Photocurrents& light,
         EventLog& log);

  const AddressMap& address_map() const { return map_; }

 private:
  AddressMap map_;
  std::vector<std::unique_ptr<sc_core::sc_module>> buses_;
  std::vector<std::unique_ptr<Pixel>> pixels_;
};

}  // namespace aesim
