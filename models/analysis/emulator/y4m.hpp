#pragma once
#include <string>
#include <vector>

#include "aesim/scene/image.hpp"

namespace aesim {

// A YUV4MPEG2 video (the raw format `ffmpeg -f yuv4mpegpipe` writes), 8-bit: the luma plane of
// every frame as an Image with values 0..255 / 255, and the frame rate of its F tag.
struct Y4mVideo {
  std::vector<Image> frames;
  double frame_rate = 25.0;
};

// Reads 4:2:0 (any siting), 4:2:2, 4:4:4 and mono; throws InputError naming the defect.
Y4mVideo read_y4m(const std::string& path);
Y4mVideo decode_y4m(const std::string& data, const std::string& path);

}  // namespace aesim
