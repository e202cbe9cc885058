#include "aesim/scene/y4m_video.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

// Real headers are a few dozen bytes: a first line longer than this is not one.
constexpr std::size_t kMostHeaderBytes = 4096;

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InputError(fmt::format("video '{}': {}", path, why));
}

// Bytes of a frame's two chroma planes, which the scene does not use.
std::size_t chroma_bytes(const std::string& chroma, std::size_t width, std::size_t height, const std::string& path) {
  const std::size_t cw = (width + 1) / 2, ch = (height + 1) / 2;
  if (chroma == "420" || chroma == "420jpeg" || chroma == "420paldv" || chroma == "420mpeg2") return 2 * cw * ch;
  if (chroma == "422") return 2 * cw * height;
  if (chroma == "444") return 2 * width * height;
  if (chroma == "mono") return 0;
  // ffmpeg writes 9- to 16-bit video as C420p10, Cmono16, ...: a camera's 10-bit (often HDR) clip.
  fail(path, fmt::format("unsupported colour space C{} (8-bit 420, 422, 444 or mono; write 8-bit grey with "
                         "ffmpeg -i CLIP -pix_fmt gray CLIP.y4m)",
                         chroma));
}

// BT.709's opto-electronic transfer function inverted (ITU-R BT.709-6, item 1.2): V = 4.5 L below
// L = 0.018, V = 1.099 L^0.45 - 0.099 above.
double bt709_to_linear(double v) { return v < 0.081 ? v / 4.5 : std::pow((v + 0.099) / 1.099, 1 / 0.45); }

struct HeaderFields {
  Y4mLayout layout;
  std::size_t chroma = 0;  // bytes of a frame's chroma planes
};

HeaderFields header_fields(const std::string& line, const std::string& path) {
  if (line.rfind("YUV4MPEG2 ", 0) != 0) fail(path, "not a YUV4MPEG2 (Y4M) file");
  long long width = 0, height = 0;
  std::string chroma = "420jpeg";
  HeaderFields h;
  std::istringstream header(line.substr(10));
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
        h.layout.frame_rate = num / den;
        if (!(num > 0 && den > 0 && std::isfinite(h.layout.frame_rate) && h.layout.frame_rate <= kMaxFrameRate)) {
          fail(path, fmt::format("frame rate F{} must be positive, finite and at most {:g} Hz", value, kMaxFrameRate));
        }
      }
      if (tag == "XCOLORRANGE=FULL") h.layout.full_range = true;
    } catch (const std::logic_error&) {
      fail(path, fmt::format("malformed header tag '{}'", tag));
    }
  }
  if (width <= 0 || height <= 0 || width > 65535 || height > 65535 || width * height > kMaxArrayPixels) {
    fail(path, fmt::format("bad frame size {}x{}", width, height));
  }
  h.layout.width = static_cast<int>(width);
  h.layout.height = static_cast<int>(height);
  h.chroma = chroma_bytes(chroma, static_cast<std::size_t>(width), static_cast<std::size_t>(height), path);
  return h;
}

Image frame_image(const Y4mLayout& layout, std::size_t k, const char* what) {
  if (k >= layout.luma.size()) throw std::logic_error(fmt::format("{}: no frame {}", what, k));
  Image img;
  img.width = layout.width;
  img.height = layout.height;
  img.pixels.resize(static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height));
  return img;
}

}  // namespace

Y4mLayout parse_y4m_header(const std::string& line, const std::string& path) { return header_fields(line, path).layout; }

Y4mLayout read_y4m_header(const std::string& path) {
  const std::string line = read_input_head(path, "video", kMostHeaderBytes);
  const std::size_t eol = line.find('\n');
  if (line.rfind("YUV4MPEG2 ", 0) != 0 || eol == std::string::npos) fail(path, "not a YUV4MPEG2 (Y4M) file");
  return parse_y4m_header(line.substr(0, eol), path);
}

Y4mLayout parse_y4m(const std::string& data, const std::string& path) {
  const std::size_t eol = data.find('\n');
  if (data.rfind("YUV4MPEG2 ", 0) != 0 || eol == std::string::npos) fail(path, "not a YUV4MPEG2 (Y4M) file");
  HeaderFields h = header_fields(data.substr(0, eol), path);
  Y4mLayout& layout = h.layout;
  const std::size_t luma = static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height);
  std::size_t pos = eol + 1;
  while (pos < data.size()) {
    const std::size_t k = layout.luma.size();
    if (k == kMaxSceneFrames) fail(path, fmt::format("more than {} frames, the most aesim reads", kMaxSceneFrames));
    if (data.compare(pos, 5, "FRAME") != 0) fail(path, fmt::format("frame {}: missing FRAME marker", k));
    const std::size_t frame_eol = data.find('\n', pos);
    if (frame_eol == std::string::npos) fail(path, fmt::format("frame {}: truncated", k));
    pos = frame_eol + 1;
    if (data.size() - pos < luma + h.chroma) fail(path, fmt::format("frame {}: truncated", k));
    layout.luma.push_back(pos);
    pos += luma + h.chroma;
  }
  if (layout.luma.empty()) fail(path, "no frames");
  return layout;
}

Image y4m_luma_codes(const std::string& data, const Y4mLayout& layout, std::size_t k) {
  Image img = frame_image(layout, k, "y4m_luma_codes");
  const auto* codes = reinterpret_cast<const unsigned char*>(data.data() + layout.luma[k]);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = codes[i] / 255.0;
  return img;
}

Image y4m_light(const std::string& data, const Y4mLayout& layout, std::size_t k) {
  Image img = frame_image(layout, k, "y4m_light");
  // One decode a code, as a table.
  const double black = layout.full_range ? 0 : 16, white = layout.full_range ? 255 : 235;
  double light[256];
  for (int c = 0; c < 256; ++c) light[c] = bt709_to_linear(std::clamp((c - black) / (white - black), 0.0, 1.0));
  const auto* codes = reinterpret_cast<const unsigned char*>(data.data() + layout.luma[k]);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = light[codes[i]];
  return img;
}

Y4mFile open_y4m(const std::string& path) {
  Y4mFile file{read_input_file(path, "video"), {}};
  file.layout = parse_y4m(file.data, path);
  return file;
}

Y4mVideo read_y4m(const std::string& path) { return decode_y4m(read_input_file(path, "video"), path); }

Y4mVideo decode_y4m(const std::string& data, const std::string& path) {
  const Y4mLayout layout = parse_y4m(data, path);
  Y4mVideo video;
  video.frame_rate = layout.frame_rate;
  for (std::size_t k = 0; k < layout.luma.size(); ++k) video.frames.push_back(y4m_luma_codes(data, layout, k));
  return video;
}

}  // namespace aesim
