#pragma once
#include <cstddef>
#include <vector>

namespace aesim {

// A grey image, row-major from the top-left, values normalised to full scale (1.0 = white;
// HDR scenes may exceed 1).
struct Image {
  int width = 0;
  int height = 0;
  std::vector<double> pixels;

  double at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

// Rec. 709 / sRGB luminance of linear red, green and blue: what every colour scene is reduced to.
inline double rec709_luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace aesim
