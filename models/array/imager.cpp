#include "array/imager.hpp"

#include <fmt/format.h>

#include "bus/ideal_bus.hpp"
#include "config/input_error.hpp"

namespace aesim {

Imager::Imager(const sc_core::sc_module_name& name, const SensorConfig& config,
               const Photocurrents& light, EventLog& log)
    : sc_module(name), map_(config.array) {
  if (config.bus.access != BusAccess::Ideal) {
    throw InputError(fmt::format("bus.access={} is not modelled yet; use bus.access=ideal",
                                 to_string(config.bus.access)));
  }
  std::vector<PixelBusIf*> tile_bus;
  for (int t = 0; t < map_.tiles(); ++t) {
    auto bus = std::make_unique<IdealBus>(fmt::format("bus_{}", t).c_str(), log);
    tile_bus.push_back(bus.get());
    buses_.push_back(std::move(bus));
  }
  pixels_.reserve(light.pixels());
  for (int y = 0; y < map_.rows(); ++y) {
    for (int x = 0; x < map_.cols(); ++x) {
      const PixelAddress p{static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)};
      AddressEvent identity;
      identity.x = p.x;
      identity.y = p.y;
      identity.tile = map_.tile_of(p);
      identity.bus_address = map_.bus_address(p);
      const std::size_t index = static_cast<std::size_t>(y) * map_.cols() + x;
      auto pixel = std::make_unique<Pixel>(fmt::format("px_{}_{}", x, y).c_str(), config, light, index,
                                           identity);
      pixel->bus.bind(*tile_bus[identity.tile]);
      pixels_.push_back(std::move(pixel));
    }
  }
}

}  // namespace aesim
