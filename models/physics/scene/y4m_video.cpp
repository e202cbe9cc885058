#include "aesim/scene/y4m_video.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

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

// A colour space tag (C420jpeg, C444p10, Cmono16, ...): the bytes of a frame's planes after luma,
// which the scene does not use, and the samples' bits. ffmpeg writes 9- to 16-bit video (a
// camera's 10-bit, often HDR, clip) as C420p10, C444p12, Cmono16 and the like, two bytes a
// sample, little-endian; C444alpha is 8-bit 4:4:4 with an alpha plane.
struct ColourSpace {
  std::size_t other_planes = 0;  // in samples
  int bits = 8;
};

ColourSpace colour_space(const std::string& chroma, std::size_t width, std::size_t height, const std::string& path) {
  const std::size_t cw = (width + 1) / 2, ch = (height + 1) / 2;
  if (chroma == "420jpeg" || chroma == "420paldv" || chroma == "420mpeg2") return {2 * cw * ch, 8};
  if (chroma == "444alpha") return {3 * width * height, 8};
  // The sampling, then the depth: "420", "420p10", "mono", "mono16".
  const bool mono = chroma.rfind("mono", 0) == 0;
  const std::size_t cut = std::min<std::size_t>(mono ? 4 : 3, chroma.size());
  const std::string sampling = chroma.substr(0, cut);
  std::string depth = chroma.substr(cut);
  if (!mono && !depth.empty()) depth = depth[0] == 'p' && depth.size() > 1 ? depth.substr(1) : "?";
  int bits = depth.empty() ? 8 : 0;
  if (depth.size() == 1 || depth.size() == 2) {
    if (depth.find_first_not_of("0123456789") == std::string::npos) bits = std::stoi(depth);
    if (bits < 9 || bits > 16) bits = 0;
  }
  if (bits != 0) {
    if (sampling == "420") return {2 * cw * ch, bits};
    if (sampling == "422") return {2 * cw * height, bits};
    if (sampling == "444") return {2 * width * height, bits};
    if (sampling == "mono") return {0, bits};
  }
  fail(path, fmt::format("unsupported colour space C{} (aesim reads 420, 422, 444 and mono, 8-bit or 9 to 16 bits as "
                         "C420p10, Cmono16; write grey with ffmpeg -i CLIP -pix_fmt gray16le CLIP.y4m)",
                         chroma));
}

// BT.709's opto-electronic transfer function inverted (ITU-R BT.709-6, item 1.2): V = 4.5 L below
// L = 0.018, V = 1.099 L^0.45 - 0.099 above.
double bt709_to_linear(double v) { return v < 0.081 ? v / 4.5 : std::pow((v + 0.099) / 1.099, 1 / 0.45); }

struct HeaderFields {
  Y4mLayout layout;
  std::size_t chroma = 0;  // bytes of a frame's planes after luma
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
  const ColourSpace space = colour_space(chroma, static_cast<std::size_t>(width), static_cast<std::size_t>(height), path);
  h.layout.bits = space.bits;
  h.chroma = space.other_planes * h.layout.sample_bytes();
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
  const std::size_t luma =
      static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height) * layout.sample_bytes();
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

namespace {

// Frame k's luma codes, each through `value` (codes above the depth's largest, which only a
// malformed file holds, are taken as the largest).
template <typename Value>
Image luma_through(const std::string& data, const Y4mLayout& layout, std::size_t k, const char* what, Value value) {
  Image img = frame_image(layout, k, what);
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data() + layout.luma[k]);
  const std::size_t most = (std::size_t(1) << layout.bits) - 1;
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const std::size_t code = layout.bits == 8 ? bytes[i] : bytes[2 * i] | static_cast<std::size_t>(bytes[2 * i + 1]) << 8;
    img.pixels[i] = value(std::min(code, most));
  }
  return img;
}

// Every code's light at a depth and range, made once for the frames that follow (a 16-bit
// video's table is 65,536 decodes, more than a small frame's pixels).
const std::vector<double>& light_table(int bits, bool full_range) {
  thread_local int table_bits = 0;
  thread_local bool table_full_range = false;
  thread_local std::vector<double> light;
  if (bits == table_bits && full_range == table_full_range) return light;
  // Video levels scale with the depth (BT.709 and BT.2020: black 64 and white 940 at 10 bits).
  const std::size_t most = (std::size_t(1) << bits) - 1;
  const double scale = std::ldexp(1.0, bits - 8);
  const double black = full_range ? 0 : 16 * scale, white = full_range ? static_cast<double>(most) : 235 * scale;
  light.resize(most + 1);
  for (std::size_t c = 0; c <= most; ++c) {
    light[c] = bt709_to_linear(std::clamp((static_cast<double>(c) - black) / (white - black), 0.0, 1.0));
  }
  table_bits = bits;
  table_full_range = full_range;
  return light;
}

}  // namespace

Image y4m_luma_codes(const std::string& data, const Y4mLayout& layout, std::size_t k) {
  const double most = std::ldexp(1.0, layout.bits) - 1;
  return luma_through(data, layout, k, "y4m_luma_codes", [most](std::size_t code) { return static_cast<double>(code) / most; });
}

Image y4m_light(const std::string& data, const Y4mLayout& layout, std::size_t k) {
  const std::vector<double>& light = light_table(layout.bits, layout.full_range);
  return luma_through(data, layout, k, "y4m_light", [&light](std::size_t code) { return light[code]; });
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
