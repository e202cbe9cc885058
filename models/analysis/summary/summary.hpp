#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "aesim/config/sensor_config.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/events/run_facts.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

// Summary JSON of docs/reference.md section 5. offered_load G = fired rate per bus * tau and throughput
// S = successfully delivered (non-ghost) rate per bus * tau, both averaged over the buses.
// With the log's per-pixel counts it adds the sizing metrics (pixel rates, dynamic range covered,
// power); with the scene the array saw (`scene`, values of full scale), the PSNR of the histogram
// reconstruction from the events delivered within analysis.window.
nlohmann::json make_summary(const SensorConfig& config, const EventLog& log, const RunFacts& facts,
                            const Image* scene = nullptr);

}  // namespace aesim
