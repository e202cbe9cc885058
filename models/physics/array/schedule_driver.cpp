#include "array/schedule_driver.hpp"

#include <algorithm>

namespace aesim {
namespace {

bool later(const AddressEvent& a, const AddressEvent& b) {
  return a.t > b.t || (a.t == b.t && (a.tile > b.tile || (a.tile == b.tile && a.bus_address > b.bus_address)));
}

}  // namespace

ScheduleDriver::ScheduleDriver(const sc_core::sc_module_name& name, const SensorConfig& config,
                               const Photocurrents& light, const AddressMap& map, std::vector<EventBus*> buses)
    : sc_module(name), buses_(std::move(buses)) {
  for (int t = 0; t < map.tiles(); ++t) {
    schedules_.push_back(std::make_unique<FiringSchedule>(config, light, map, static_cast<std::uint32_t>(t)));
    Head h;
    h.tile = static_cast<std::size_t>(t);
    if (schedules_.back()->next(h.firing)) heads_.push_back(h);
  }
  auto cmp = [](const Head& a, const Head& b) { return later(a.firing, b.firing); };
  std::make_heap(heads_.begin(), heads_.end(), cmp);
  SC_THREAD(run);
}

void ScheduleDriver::run() {
  auto cmp = [](const Head& a, const Head& b) { return later(a.firing, b.firing); };
  while (!heads_.empty()) {
    std::pop_heap(heads_.begin(), heads_.end(), cmp);
    Head& h = heads_.back();
    const sc_core::sc_time at(h.firing.t, sc_core::SC_SEC);
    if (at > sc_core::sc_time_stamp()) wait(at - sc_core::sc_time_stamp());
    buses_[h.tile]->request(h.firing);
    if (schedules_[h.tile]->next(h.firing)) {
      std::push_heap(heads_.begin(), heads_.end(), cmp);
    } else {
      heads_.pop_back();
    }
  }
}

}  // namespace aesim
