#include "rungs/imager.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "array/firing_schedule.hpp"
#include "array/fixed_step_array.hpp"
#include "array/queue_model.hpp"
#include "array/schedule_driver.hpp"
#include "bus/aloha_bus.hpp"
#include "bus/clocked_aloha_bus.hpp"
#include "bus/ideal_bus.hpp"
#include "errors/input_error.hpp"

namespace aesim {
namespace {

std::unique_ptr<TileBus> make_bus(const std::string& name, std::uint32_t tile, const SensorConfig& c,
                                  Fidelity fidelity, const AddressMap& map, EventLog& log, VcdRecorder* vcd,
                                  const CycleOptions& cycle) {
  if (fidelity == Fidelity::Cycle) {
    if (c.bus.access != BusAccess::Aloha) {
      throw InputError(fmt::format("bus.access={} has no cycle-level model; the cycle fidelity models the "
                                   "aloha bus (use sim.fidelity=event)", to_string(c.bus.access)));
    }
    if (map.bus_bits() > kReceiverAddrWidth) {
      throw InputError(fmt::format("array.tile_rows: a {}-bit tile address exceeds the receiver's {} address bits",
                                   map.bus_bits(), kReceiverAddrWidth));
    }
    if (static_cast<unsigned>(c.receiver.fifo_depth) > kReceiverFifoCapacity) {
      throw InputError(fmt::format("receiver.fifo_depth: at most {} at the cycle fidelity (the receiver's FIFO)",
                                   kReceiverFifoCapacity));
    }
    if (std::round(c.receiver.tick * c.receiver.clock) > kReceiverMaxPrescale) {
      throw InputError(fmt::format("receiver.tick: at most {} clock cycles per tick", kReceiverMaxPrescale));
    }
    return std::make_unique<ClockedAlohaBus>(name.c_str(), tile, map, c, log, vcd, cycle);
  }
  switch (c.bus.access) {
    case BusAccess::Ideal: return std::make_unique<IdealBus>(name.c_str(), log);
    case BusAccess::Aloha:
      return std::make_unique<AlohaBus>(name.c_str(), log, map, c.bus.t_event, c.bus.contention_detect);
    case BusAccess::Arbitrated:
      return std::make_unique<ArbitratedBus>(name.c_str(), log, c.bus.t_event, c.sim.duration);
  }
  throw std::logic_error("unknown bus access");
}

}  // namespace

Imager::Imager(const sc_core::sc_module_name& name, const SensorConfig& config, Fidelity fidelity,
               const Photocurrents& light, EventLog& log, VcdRecorder* vcd, const CycleOptions& cycle)
    : sc_module(name), config_(config), map_(config.array) {
  for (int t = 0; t < map_.tiles(); ++t) {
    buses_.push_back(make_bus(fmt::format("tile{}", t), static_cast<std::uint32_t>(t), config, fidelity, map_,
                              log, vcd, cycle));
  }
  if (fidelity == Fidelity::Event || fidelity == Fidelity::Queue) return;  // run_schedule(), run_queue()
  if (fidelity == Fidelity::FixedStep) {
    std::vector<TileBus*> buses;
    for (auto& b : buses_) buses.push_back(b.get());
    driver_ = std::make_unique<FixedStepArray>("fixed_step", config, light, map_, std::move(buses));
    return;
  }
  if (fidelity == Fidelity::Cycle) {
    // One process feeds the clocked buses from the tiles' schedules.
    std::vector<TileBus*> buses;
    for (auto& b : buses_) buses.push_back(b.get());
    driver_ = std::make_unique<ScheduleDriver>("schedule", config, light, map_, std::move(buses));
    return;
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
      pixel->bus.bind(*buses_[identity.tile]);
      pixels_.push_back(std::move(pixel));
    }
  }
}

void Imager::run_schedule(const Photocurrents& light, int threads) {
  const int tiles = map_.tiles();
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = std::min(threads, tiles);
  std::atomic<int> next_tile{0};
  auto work = [&] {
    for (int t = next_tile++; t < tiles; t = next_tile++) {
      FiringSchedule schedule(config_, light, map_, static_cast<std::uint32_t>(t));
      TileBus& bus = *buses_[static_cast<std::size_t>(t)];
      AddressEvent firing;
      while (schedule.next(firing)) bus.request(firing);
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
}

void Imager::run_queue(const Photocurrents& light) {
  for (const AddressEvent& e : queue_events(config_, light, map_, &empty_queue_frames_)) buses_[e.tile]->request(e);
}

std::uint64_t Imager::multi_fire_steps() const {
  const auto* fixed = dynamic_cast<const FixedStepArray*>(driver_.get());
  return fixed ? fixed->multi_fire_steps() : 0;
}

void Imager::finish() {
  for (auto& bus : buses_) bus->finish();
}

double Imager::tau() const {
  double sum = 0;
  int measured = 0;
  for (const auto& bus : buses_) {
    if (bus->measured_tau() > 0) {
      sum += bus->measured_tau();
      ++measured;
    }
  }
  return measured > 0 ? sum / measured : config_.bus.t_event;
}

Imager::CycleStats Imager::cycle_stats() const {
  CycleStats s;
  for (const auto& bus : buses_) {
    const auto* clocked = dynamic_cast<const ClockedAlohaBus*>(bus.get());
    if (!clocked) continue;
    s.protocol_violations += clocked->protocol_violations();
    s.clock_edges += clocked->clock_edges();
    s.scoreboard_beats += clocked->receiver().scoreboard_beats();
    s.scoreboard_mismatches += clocked->receiver().scoreboard_mismatches();
  }
  return s;
}

}  // namespace aesim
