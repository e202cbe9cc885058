#pragma once
#include <string>
#include <vector>

#include "aesim/scene/scene.hpp"

namespace aesim {

// A command's settings in the order they apply: the --set overrides, then the options that name
// a key of their own (--duration: sim.duration, --max-events: sim.max_events) when given.
std::vector<Setting> command_settings(const std::vector<std::string>& sets, const std::string& duration,
                                      const std::string& max_events);

}  // namespace aesim
