#include "aesim/compare/fidelity_errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "aesim/recon/reconstruct.hpp"

namespace aesim {
namespace {

std::unordered_map<std::uint64_t, std::vector<double>> fire_times(const EventLog& log) {
  std::unordered_map<std::uint64_t, std::vector<double>> by_pixel;
  for (const TruthRecord& t : log.truth()) {
    by_pixel[(std::uint64_t(t.firing.y) << 32) | t.firing.x].push_back(t.firing.t);
  }
  return by_pixel;
}

}  // namespace

double psnr_db(const Image& image, const Image& reference) {
  return psnr_db(
      reference.pixels.size(), [&image](std::size_t i) { return image.pixels[i]; },
      [&reference](std::size_t i) { return reference.pixels[i]; });
}

FidelityErrors fidelity_errors(const EventLog& reference, const EventLog& run, const Image& scene) {
  FidelityErrors e;
  const auto ref = fire_times(reference);
  const auto got = fire_times(run);
  double count_diff = 0, count_ref = 0, sq = 0, pairs = 0;
  for (const auto& [pixel, times] : ref) {
    count_ref += static_cast<double>(times.size());
    const auto it = got.find(pixel);
    const std::size_t n = it == got.end() ? 0 : it->second.size();
    count_diff += std::abs(static_cast<double>(n) - static_cast<double>(times.size()));
    for (std::size_t k = 0; k < std::min(n, times.size()); ++k) {
      const double d = it->second[k] - times[k];
      sq += d * d;
      pairs += 1;
    }
  }
  for (const auto& [pixel, times] : got) {
    if (!ref.count(pixel)) count_diff += static_cast<double>(times.size());
  }
  e.count_error = count_ref > 0 ? count_diff / count_ref : 0.0;
  e.rms_time_error_s = pairs > 0 ? std::sqrt(sq / pairs) : 0.0;
  e.collision_fraction = run.totals().collision_fraction();
  e.collision_fraction_error = std::abs(e.collision_fraction - reference.totals().collision_fraction());

  std::vector<AddressEvent> good;
  for (const AddressEvent& ev : run.events()) {
    if (!(ev.flags & kGhostEvent)) good.push_back(ev);
  }
  Image truth = scene;
  const double peak = *std::max_element(truth.pixels.begin(), truth.pixels.end());
  if (peak > 0) {
    for (double& v : truth.pixels) v /= peak;
  }
  e.psnr_db = psnr_db(reconstruct(good, scene.width, scene.height, ReconMode::Histogram), truth);
  return e;
}

}  // namespace aesim
