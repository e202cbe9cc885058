#include "aesim/scene/reduced_image.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

bool ReducedImage::decodable(long long width, long long height) {
  return width >= 1 && height >= 1 && width <= 65535 && height <= 65535 && width * height <= kMaxDecodedPixels;
}

void ReducedImage::check(long long width, long long height, const std::string& path) {
  if (!decodable(width, height)) {
    throw InputError(fmt::format("scene file '{}': {}x{} is more than the {} pixels (sides up to 65535) aesim decodes",
                                 path, width, height, kMaxDecodedPixels));
  }
}

ReducedImage::ReducedImage(long long width, long long height, const std::string& path) : width_(width), height_(height) {
  check(width, height, path);
  const auto blocks = [&](long long side) { return (side + k_ - 1) / k_; };
  while (blocks(width) * blocks(height) > kMaxArrayPixels) ++k_;
  out_.width = static_cast<int>(blocks(width));
  out_.height = static_cast<int>(blocks(height));
  out_.pixels.reserve(static_cast<std::size_t>(out_.width) * out_.height);
  if (k_ > 1) sums_.assign(static_cast<std::size_t>(out_.width), 0.0);
}

void ReducedImage::add_row(const double* light) {
  ++rows_in_;
  if (k_ == 1) {
    out_.pixels.insert(out_.pixels.end(), light, light + width_);
    return;
  }
  for (long long x = 0; x < width_; ++x) sums_[static_cast<std::size_t>(x / k_)] += light[x];
  if (++band_rows_ == k_ || rows_in_ == height_) close_band();
}

void ReducedImage::close_band() {
  for (int bx = 0; bx < out_.width; ++bx) {
    const long long columns = std::min<long long>(k_, width_ - static_cast<long long>(bx) * k_);
    out_.pixels.push_back(sums_[bx] / static_cast<double>(columns * band_rows_));
  }
  std::fill(sums_.begin(), sums_.end(), 0.0);
  band_rows_ = 0;
}

Image ReducedImage::take() { return std::move(out_); }

}  // namespace aesim
