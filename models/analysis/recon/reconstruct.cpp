#include "aesim/recon/reconstruct.hpp"

#include <algorithm>
#include <limits>

namespace aesim {
namespace {

void normalise_to_peak(Image& img) {
  const double peak = img.pixels.empty() ? 0.0 : *std::max_element(img.pixels.begin(), img.pixels.end());
  if (peak > 0) {
    for (double& v : img.pixels) v /= peak;
  }
}

}  // namespace

void scale_to_percentile(Image& img, double percentile) {
  std::vector<double> lit;
  for (double v : img.pixels) {
    if (v > 0) lit.push_back(v);
  }
  if (lit.empty()) return;
  const auto at = static_cast<std::size_t>(std::clamp(percentile / 100.0, 0.0, 1.0) * static_cast<double>(lit.size() - 1));
  std::nth_element(lit.begin(), lit.begin() + static_cast<long>(at), lit.end());
  const double level = lit[at];
  if (!(level > 0)) return;
  for (double& v : img.pixels) v = std::min(1.0, v / level);
}

Image histogram_image(const std::vector<std::uint32_t>& counts, int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  img.pixels.assign(counts.begin(), counts.end());
  normalise_to_peak(img);
  return img;
}

Image reconstruct(const std::vector<AddressEvent>& events, int width, int height, ReconMode mode) {
  Image img;
  img.width = width;
  img.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  img.pixels.assign(n, 0.0);
  if (mode == ReconMode::Histogram) {
    for (const AddressEvent& e : events) {
      if (e.x < static_cast<std::uint32_t>(width) && e.y < static_cast<std::uint32_t>(height)) {
        img.pixels[static_cast<std::size_t>(e.y) * width + e.x] += 1.0;
      }
    }
  } else {
    const double unseen = -std::numeric_limits<double>::infinity();
    std::vector<double> last(n, unseen), previous(n, unseen);
    for (const AddressEvent& e : events) {
      if (e.x >= static_cast<std::uint32_t>(width) || e.y >= static_cast<std::uint32_t>(height)) continue;
      const std::size_t i = static_cast<std::size_t>(e.y) * width + e.x;
      previous[i] = last[i];
      last[i] = e.t;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double dt = last[i] - previous[i];
      // Two events in one timestamp tick give dt = 0: brighter than resolvable, so leave it to
      // the normalisation below by treating it as the brightest finite rate seen.
      if (previous[i] != unseen) img.pixels[i] = dt > 0 ? 1.0 / dt : std::numeric_limits<double>::max();
    }
    double finite_max = 0;
    for (double v : img.pixels) {
      if (v < std::numeric_limits<double>::max()) finite_max = std::max(finite_max, v);
    }
    for (double& v : img.pixels) {
      if (v == std::numeric_limits<double>::max()) v = finite_max > 0 ? finite_max : 1.0;
    }
  }
  normalise_to_peak(img);
  return img;
}

std::vector<AddressEvent> first_events(const std::vector<AddressEvent>& events, std::size_t count) {
  return {events.begin(), events.begin() + static_cast<std::ptrdiff_t>(std::min(count, events.size()))};
}

std::vector<AddressEvent> first_window(const std::vector<AddressEvent>& events, double window) {
  if (events.empty()) return {};
  const double end = events.front().t + window;
  auto last = std::find_if(events.begin(), events.end(), [end](const AddressEvent& e) { return e.t >= end; });
  return {events.begin(), last};
}

}  // namespace aesim
