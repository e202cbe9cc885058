#include "command_settings.hpp"

namespace aesim {

std::vector<Setting> command_settings(const std::vector<std::string>& sets, const std::string& duration,
                                      const std::string& max_events) {
  std::vector<Setting> settings;
  for (const std::string& s : sets) settings.push_back(parse_setting(s));
  if (!duration.empty()) settings.emplace_back("sim.duration", duration);
  if (!max_events.empty()) settings.emplace_back("sim.max_events", max_events);
  return settings;
}

}  // namespace aesim
