#pragma once
#include <cstdint>
#include <string>

#include "description/receiver_description.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

// A scene run: the busiest tile of the 64x64 ALOHA imager (four 32x32 tiles, 10-bit bus) looking
// at `scene`, its pixels' light scaled so that the bus sees offered load `load` (G = lambda * tau,
// tau taken as ack_latency_cycles' min + max clock periods: Req rise to Ack fall), with 2 %
// threshold mismatch and random starting charge drawn from `seed`, for about `firings` firings.
// The consumer is ready at each edge with probability `ready`.
struct SceneLoad {
  std::string scene;
  double load = 0.3;
  std::uint64_t seed = 1;
  double firings = 2000;
  double ready = 1;
};

// The bus address width of that imager's tiles.
inline constexpr int kVerifyBusBits = 10;

VerifyCase scene_case(const SceneLoad& load, const ReceiverDescription& d);

}  // namespace aesim
