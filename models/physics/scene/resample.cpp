#include "aesim/scene/resample.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace aesim {
namespace {

struct Span {
  int first;
  std::vector<double> weights;  // overlap of each source pixel, in source-pixel units
};

// For each output index, which source pixels it covers along one axis and by how much.
std::vector<Span> spans(int in_size, int out_size) {
  std::vector<Span> out(static_cast<std::size_t>(out_size));
  const double ratio = static_cast<double>(in_size) / out_size;
  for (int o = 0; o < out_size; ++o) {
    const double lo = o * ratio;
    const double hi = (o + 1) * ratio;
    Span& s = out[static_cast<std::size_t>(o)];
    s.first = static_cast<int>(std::floor(lo));
    const int last = std::min(in_size - 1, static_cast<int>(std::ceil(hi)) - 1);
    for (int i = s.first; i <= last; ++i) {
      s.weights.push_back(std::min<double>(hi, i + 1) - std::max<double>(lo, i));
    }
  }
  return out;
}

}  // namespace

Image resample_area(const Image& in, int width, int height) {
  if (in.width == width && in.height == height) return in;
  const auto xs = spans(in.width, width);
  const auto ys = spans(in.height, height);
  Image out;
  out.width = width;
  out.height = height;
  out.pixels.resize(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    const Span& sy = ys[static_cast<std::size_t>(y)];
    for (int x = 0; x < width; ++x) {
      const Span& sx = xs[static_cast<std::size_t>(x)];
      double sum = 0, area = 0;
      for (std::size_t j = 0; j < sy.weights.size(); ++j) {
        for (std::size_t i = 0; i < sx.weights.size(); ++i) {
          const double w = sy.weights[j] * sx.weights[i];
          sum += w * in.at(sx.first + static_cast<int>(i), sy.first + static_cast<int>(j));
          area += w;
        }
      }
      out.pixels[static_cast<std::size_t>(y) * width + x] = sum / area;
    }
  }
  return out;
}

}  // namespace aesim
