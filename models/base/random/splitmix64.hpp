#pragma once
#include <cstdint>
#include <limits>

namespace aesim {

// An 8-byte random engine (SplitMix64, passes BigCrush) so that every pixel can own a stream:
// results then depend only on (seed, pixel, purpose), never on the order pixels are simulated.
class SplitMix64 {
 public:
  using result_type = std::uint64_t;
  explicit SplitMix64(std::uint64_t seed = 0) : state_(seed) {}
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

// Independent streams for one run: mixing the purpose and the index into the seed decorrelates
// neighbouring pixels even with seed 0.
enum class Stream : std::uint64_t { Threshold = 1, InitialCharge = 2, ShotNoise = 3, EmulatorChaos = 4, VerifyReady = 5,
                                    VerifyClockPhase = 6 };

inline SplitMix64 stream_for(std::uint64_t seed, Stream purpose, std::uint64_t index) {
  SplitMix64 mix(seed ^ (static_cast<std::uint64_t>(purpose) * 0xD1B54A32D192ED03ULL));
  const std::uint64_t base = mix();
  SplitMix64 per_index(base + index * 0x9E3779B97F4A7C15ULL);
  return SplitMix64(per_index());
}

// Uniform in [0, 1) from the top 53 bits; the same on every platform, unlike
// std::uniform_real_distribution whose algorithm is left to the library.
inline double uniform01(SplitMix64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace aesim
