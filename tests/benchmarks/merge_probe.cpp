#include "merge_probe.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <queue>

#include "aesim/config/sensor_config.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"

namespace aesim {

RecordedWindows record_qcif_windows(std::size_t windows) {
  SensorConfig c = load_sensor("aloha");
  c.array.rows = 144;
  c.array.cols = 176;
  c.sim.duration = 20.0;
  c.sim.fidelity = Fidelity::Event;
  const Scene scene = load_scene(find_scene(std::string(AESIM_SOURCE_DIR) + "/scenes/uniform.pgm"), c.array, c.scene);
  const ResolvedConfig config = c.resolved();
  EventCollector collected;
  SimulationRequest request;
  request.keep_events = true;
  request.stream = &collected;
  simulate(config, Photocurrents(scene, c.pixel), request);
  const std::vector<AddressEvent>& events = collected.events();
  std::size_t tiles = 0;
  for (const AddressEvent& e : events) tiles = std::max<std::size_t>(tiles, e.tile + 1);
  RecordedWindows r;
  r.events = events.size();
  const std::size_t per_window = (events.size() + windows - 1) / windows;
  for (std::size_t at = 0; at < events.size(); at += per_window) {
    const std::size_t end = std::min(events.size(), at + per_window);
    TileRecords batch(tiles);
    for (std::size_t i = at; i < end; ++i) batch.events[events[i].tile].push_back(TileEvent::of(events[i]));
    r.windows.push_back(std::move(batch));
    r.before.push_back(end < events.size() ? events[end].t : events.back().t + 1);
  }
  return r;
}

std::uint64_t merge_probe(const RecordedWindows& recorded) {
  struct Head {
    double t;
    std::uint32_t tile, address;
    std::uint32_t index;
    bool operator>(const Head& o) const {
      return t != o.t ? t > o.t : tile != o.tile ? tile > o.tile : address > o.address;
    }
  };
  std::vector<std::uint64_t> out;
  out.reserve(1 << 14);
  std::uint64_t made = 0;
  std::vector<Head> storage;
  for (const TileRecords& w : recorded.windows) {
    storage.clear();
    std::priority_queue<Head, std::vector<Head>, std::greater<Head>> heap(std::greater<Head>(), std::move(storage));
    const auto head_of = [&](std::uint32_t tile, std::uint32_t index) {
      const TileEvent& e = w.events[tile][index];
      return Head{e.t, tile, e.address_ghost & ~TileEvent::kGhostBit, index};
    };
    for (std::uint32_t tile = 0; tile < w.events.size(); ++tile) {
      if (!w.events[tile].empty()) heap.push(head_of(tile, 0));
    }
    while (!heap.empty()) {
      const Head h = heap.top();
      heap.pop();
      out.push_back((std::uint64_t(h.address) << 32) | static_cast<std::uint32_t>(h.t * 1e6));
      if (out.size() == out.capacity()) {
        benchmark::DoNotOptimize(out.data());
        out.clear();
      }
      ++made;
      if (h.index + 1 < w.events[h.tile].size()) heap.push(head_of(h.tile, h.index + 1));
    }
  }
  benchmark::DoNotOptimize(out.data());
  return made;
}

}  // namespace aesim
