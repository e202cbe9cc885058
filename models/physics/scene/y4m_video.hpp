#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "aesim/scene/image.hpp"

namespace aesim {

// A YUV4MPEG2 (Y4M) video, the raw format `ffmpeg -f yuv4mpegpipe` writes: 4:2:0 (any siting),
// 4:2:2, 4:4:4 or mono, 8-bit or 9 to 16 bits (two bytes a sample, little-endian), luma taken.
// Where its frames lie in the file's bytes, and what its header says of them.
struct Y4mLayout {
  int width = 0, height = 0;
  double frame_rate = 25.0;  // the F tag, Hz
  // ffmpeg's XCOLORRANGE=FULL: luma codes span 0..255. Otherwise (XCOLORRANGE=LIMITED, or no such
  // tag, as Y4M's own default) video levels: black at 16, white at 235.
  bool full_range = false;
  int bits = 8;  // a sample's: 8, or 9 to 16 as the colour space's pN (C420p10) says
  std::size_t sample_bytes() const { return bits > 8 ? 2 : 1; }
  std::vector<std::size_t> luma;  // where each frame's luma plane starts
};

// The header line's layout (no frames yet); throws InputError naming the tag at fault.
Y4mLayout parse_y4m_header(const std::string& line, const std::string& path);
// The header of a Y4M file, from its first line alone (a scene's frame rate is known before its
// frames are read).
Y4mLayout read_y4m_header(const std::string& path);
// Every frame of a whole file; throws InputError naming the defect.
Y4mLayout parse_y4m(const std::string& data, const std::string& path);

// A Y4M file's bytes, bounded, and its frames' layout.
struct Y4mFile {
  std::string data;
  Y4mLayout layout;
};
Y4mFile open_y4m(const std::string& path);

// Frame k's luma codes over the largest (255 at 8 bits), as they are (the source paper's emulator
// takes grey levels).
Image y4m_luma_codes(const std::string& data, const Y4mLayout& layout, std::size_t k);
// Frame k as light, a fraction of full scale: the luma code's level (video or full range, codes
// past black and white clipped to them) decoded with the inverse of BT.709's transfer function
// (the camera's encoding undone: a level of 0.5 is 26 % of full-scale light, not 50 %).
Image y4m_light(const std::string& data, const Y4mLayout& layout, std::size_t k);

// The emulator's frames: every frame's luma codes over 255, and the frame rate.
struct Y4mVideo {
  std::vector<Image> frames;
  double frame_rate = 25.0;
};
Y4mVideo read_y4m(const std::string& path);
Y4mVideo decode_y4m(const std::string& data, const std::string& path);

}  // namespace aesim
