#include "aesim/emulator/behaviours.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

Image zero_below(Image img, double threshold) {
  for (double& v : img.pixels) v = v > threshold ? v : 0.0;
  return img;
}

}  // namespace

Behaviour parse_behaviour(const std::string& name) {
  if (name == "intensity") return Behaviour::Intensity;
  if (name == "motion") return Behaviour::Motion;
  if (name == "edge") return Behaviour::Edge;
  if (name == "centroid") return Behaviour::Centroid;
  throw InputError(fmt::format("--behaviour: expected intensity, motion, edge or centroid (got '{}')", name));
}

Image clip_levels(const Image& frame, double low, double high) {
  Image out = frame;
  for (double& v : out.pixels) v = v < low ? 0.0 : std::min(v, high);
  return out;
}

Image intensity_map(const Image& frame, double threshold) { return zero_below(frame, threshold); }

Image motion_map(const Image& frame, const Image& previous, double threshold) {
  Image out = frame;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = std::fabs(frame.pixels[i] - previous.pixels[i]);
  return zero_below(std::move(out), threshold);
}

Image edge_map(const Image& frame, double threshold) {
  Image out = frame;
  auto at = [&](int x, int y) {
    return frame.at(std::clamp(x, 0, frame.width - 1), std::clamp(y, 0, frame.height - 1));
  };
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const double gx = (at(x + 1, y - 1) + 2 * at(x + 1, y) + at(x + 1, y + 1)) -
                        (at(x - 1, y - 1) + 2 * at(x - 1, y) + at(x - 1, y + 1));
      const double gy = (at(x - 1, y + 1) + 2 * at(x, y + 1) + at(x + 1, y + 1)) -
                        (at(x - 1, y - 1) + 2 * at(x, y - 1) + at(x + 1, y - 1));
      // A unit step gives |g| = 4 across it.
      out.pixels[static_cast<std::size_t>(y) * frame.width + x] = std::min(1.0, std::hypot(gx, gy) / 4.0);
    }
  }
  return zero_below(std::move(out), threshold);
}

std::optional<std::pair<double, double>> motion_centroid(const Image& frame, const Image& previous, double threshold) {
  const Image m = motion_map(frame, previous, threshold);
  double sx = 0, sy = 0, n = 0;
  for (int y = 0; y < m.height; ++y) {
    for (int x = 0; x < m.width; ++x) {
      if (m.at(x, y) > 0) {
        sx += x;
        sy += y;
        n += 1;
      }
    }
  }
  if (n == 0) return std::nullopt;
  return std::make_pair(sx / n, sy / n);
}

}  // namespace aesim
