#include "aesim/scene/exif_orientation.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace aesim {

int exif_orientation(const unsigned char* tiff, std::size_t size) {
  if (tiff == nullptr || size < 8) return 1;
  bool big;
  if (tiff[0] == 'I' && tiff[1] == 'I') {
    big = false;
  } else if (tiff[0] == 'M' && tiff[1] == 'M') {
    big = true;
  } else {
    return 1;
  }
  const auto u16 = [&](std::size_t at) -> std::uint32_t {
    return big ? (std::uint32_t(tiff[at]) << 8) | tiff[at + 1] : (std::uint32_t(tiff[at + 1]) << 8) | tiff[at];
  };
  const auto u32 = [&](std::size_t at) -> std::uint32_t { return big ? (u16(at) << 16) | u16(at + 2) : (u16(at + 2) << 16) | u16(at); };
  if (u16(2) != 42) return 1;
  const std::uint32_t ifd = u32(4);
  if (ifd < 8 || ifd > size - 2) return 1;
  const std::uint32_t entries = u16(ifd);
  // Each entry is 12 bytes: tag, type, count, and the value itself when it fits 4 bytes.
  for (std::uint32_t i = 0; i < entries; ++i) {
    const std::size_t at = std::size_t(ifd) + 2 + std::size_t(i) * 12;
    if (at + 12 > size) return 1;
    if (u16(at) != 0x0112) continue;
    constexpr std::uint32_t kShort = 3;
    if (u16(at + 2) != kShort || u32(at + 4) != 1) return 1;
    const std::uint32_t value = u16(at + 8);
    return value >= 1 && value <= 8 ? static_cast<int>(value) : 1;
  }
  return 1;
}

void apply_exif_orientation(Image& img, int orientation) {
  if (orientation < 2 || orientation > 8) return;
  const int w = img.width, h = img.height;
  const bool swapped = orientation >= 5;
  const int out_w = swapped ? h : w;
  std::vector<double> out(img.pixels.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Where the stored pixel (x, y) is shown.
      int sx = x, sy = y;
      switch (orientation) {
        case 2: sx = w - 1 - x; break;
        case 3: sx = w - 1 - x, sy = h - 1 - y; break;
        case 4: sy = h - 1 - y; break;
        case 5: sx = y, sy = x; break;
        case 6: sx = h - 1 - y, sy = x; break;
        case 7: sx = h - 1 - y, sy = w - 1 - x; break;
        case 8: sx = y, sy = w - 1 - x; break;
        default: break;
      }
      out[static_cast<std::size_t>(sy) * out_w + sx] = img.pixels[static_cast<std::size_t>(y) * w + x];
    }
  }
  img.pixels = std::move(out);
  if (swapped) std::swap(img.width, img.height);
}

}  // namespace aesim
