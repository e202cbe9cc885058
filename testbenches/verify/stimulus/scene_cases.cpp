#include "stimulus/scene_cases.hpp"

#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "aesim/array/address_map.hpp"
#include "aesim/array/firing_schedule.hpp"
#include "driver/case_driver.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {
namespace {

// One tile's firings from the exact event-driven model (the cycle rung's schedule), in ps.
class SceneFirings : public FiringSource {
 public:
  SceneFirings(std::shared_ptr<const Photocurrents> photocurrents, const PixelParams& pixel, const SimParams& sim,
               const AddressMap& map, std::uint32_t tile)
      : photocurrents_(std::move(photocurrents)), map_(map), schedule_(pixel, sim, *photocurrents_, map_, tile) {}
  bool next(Firing& f) override {
    AddressEvent e;
    if (!schedule_.next(e)) return false;
    f.t_ps = static_cast<std::uint64_t>(std::llround(e.t * 1e12));
    f.addr = e.bus_address;
    return true;
  }

 private:
  std::shared_ptr<const Photocurrents> photocurrents_;
  AddressMap map_;
  FiringSchedule schedule_;
};

}  // namespace

VerifyCase scene_case(const SceneLoad& load, const ReceiverDescription& d) {
  ArrayParams array;  // 64 x 64 in 32 x 32 tiles
  const AddressMap map(array);
  PixelParams pixel;
  pixel.mismatch = 0.02;
  pixel.initial = InitialState::Random;
  const Scene scene = load_scene(find_scene(load.scene), array, SceneParams{});

  // Pick the tile with the most light, then scale i_max so that its pixels fire at the rate the
  // load asks for: lambda = sum(I) / (c_int * dv_int) with no reset time or dark current.
  const Photocurrents probe(scene, pixel);
  std::vector<double> light(static_cast<std::size_t>(map.tiles()), 0.0);
  for (int y = 0; y < array.rows; ++y) {
    for (int x = 0; x < array.cols; ++x) {
      const PixelAddress p{static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)};
      light[map.tile_of(p)] += probe.current(0, static_cast<std::size_t>(y) * array.cols + x);
    }
  }
  const std::uint32_t tile = static_cast<std::uint32_t>(std::max_element(light.begin(), light.end()) - light.begin());
  if (!(light[tile] > 0)) throw InputError(fmt::format("scene '{}' is dark: no pixel would fire", load.scene));
  const double period = 1.0 / d.clock_hz;
  const double tau = (d.ack_latency_min + d.ack_latency_max) * period;
  const double lambda = load.load / tau;
  const double lambda_probe = light[tile] / pixel.threshold_charge();
  pixel.i_max *= lambda / lambda_probe;

  SimParams sim;
  sim.seed = load.seed;
  sim.duration = load.firings / lambda;
  auto photocurrents = std::make_shared<const Photocurrents>(scene, pixel);

  VerifyCase c;
  c.name = fmt::format("scene G={} ready={} seed={}", load.load, load.ready, load.seed);
  c.kind = "scene";
  c.seed = load.seed;
  c.ready_probability = load.ready;
  c.expected_firings = load.firings;
  c.make_firings = [photocurrents, pixel, sim, map, tile] {
    return std::make_unique<SceneFirings>(photocurrents, pixel, sim, map, tile);
  };
  const double edges = sim.duration / period;
  c.max_edges = static_cast<std::uint64_t>(edges * 1.5) + 100000;
  return c;
}

}  // namespace aesim
