#include "aesim/emulator/y4m.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

Y4mVideo read_y4m(const std::string& path) { return decode_y4m(read_input_file(path, "video"), path); }

Y4mVideo decode_y4m(const std::string& data, const std::string& path) {
  auto fail = [&](const std::string& why) { throw InputError(fmt::format("video '{}': {}", path, why)); };
  const std::size_t eol = data.find('\n');
  if (data.rfind("YUV4MPEG2 ", 0) != 0 || eol == std::string::npos) fail("not a YUV4MPEG2 (Y4M) file");
  long long width = 0, height = 0;
  std::string chroma = "420jpeg";
  Y4mVideo video;
  std::istringstream header(data.substr(10, eol - 10));
  std::string tag;
  while (header >> tag) {
    const std::string value = tag.substr(1);
    try {
      if (tag[0] == 'W') width = std::stoll(value);
      if (tag[0] == 'H') height = std::stoll(value);
      if (tag[0] == 'C') chroma = value;
      if (tag[0] == 'F') {
        const auto colon = value.find(':');
        const double num = std::stod(value.substr(0, colon));
        const double den = colon == std::string::npos ? 1.0 : std::stod(value.substr(colon + 1));
        video.frame_rate = num / den;
        if (!(num > 0 && den > 0 && std::isfinite(video.frame_rate) && video.frame_rate <= kMaxFrameRate)) {
          fail(fmt::format("frame rate F{} must be positive, finite and at most {:g} Hz", value, kMaxFrameRate));
        }
      }
    } catch (const std::logic_error&) {
      fail(fmt::format("malformed header tag '{}'", tag));
    }
  }
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535 || width * height > kMaxArrayPixels) {
    fail(fmt::format("bad frame size {}x{}", width, height));
  }
  const std::size_t luma = static_cast<std::size_t>(width * height);
  const std::size_t cw = static_cast<std::size_t>((width + 1) / 2), ch = static_cast<std::size_t>((height + 1) / 2);
  std::size_t chroma_bytes = 0;
  if (chroma == "420" || chroma == "420jpeg" || chroma == "420paldv" || chroma == "420mpeg2") chroma_bytes = 2 * cw * ch;
  else if (chroma == "422") chroma_bytes = 2 * cw * static_cast<std::size_t>(height);
  else if (chroma == "444") chroma_bytes = 2 * luma;
  else if (chroma == "mono") chroma_bytes = 0;
  else fail(fmt::format("unsupported colour space C{} (8-bit 420, 422, 444 or mono)", chroma));

  std::size_t pos = eol + 1;
  while (pos < data.size()) {
    if (video.frames.size() == kMaxSceneFrames) fail(fmt::format("more than {} frames, the most aesim reads", kMaxSceneFrames));
    if (data.compare(pos, 5, "FRAME") != 0) fail(fmt::format("frame {}: missing FRAME marker", video.frames.size()));
    const std::size_t frame_eol = data.find('\n', pos);
    if (frame_eol == std::string::npos) fail(fmt::format("frame {}: truncated", video.frames.size()));
    pos = frame_eol + 1;
    if (data.size() < pos + luma + chroma_bytes) fail(fmt::format("frame {}: truncated", video.frames.size()));
    Image img;
    img.width = static_cast<int>(width);
    img.height = static_cast<int>(height);
    img.pixels.resize(luma);
    for (std::size_t i = 0; i < luma; ++i) img.pixels[i] = static_cast<unsigned char>(data[pos + i]) / 255.0;
    video.frames.push_back(std::move(img));
    pos += luma + chroma_bytes;
  }
  if (video.frames.empty()) fail("no frames");
  return video;
}

}  // namespace aesim
