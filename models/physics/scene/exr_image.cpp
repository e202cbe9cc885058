#include "aesim/scene/exr_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfRgbaFile.h>
#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/scene_file.hpp"

namespace aesim {
namespace {

// The file's bytes, already read (and bounded) by read_scene_file, as OpenEXR's input stream.
class MemoryStream : public Imf::IStream {
 public:
  MemoryStream(const std::string& data, const std::string& name) : Imf::IStream(name.c_str()), data_(data) {}
  bool isMemoryMapped() const override { return false; }
  bool read(char c[], int n) override {
    if (n < 0 || static_cast<std::size_t>(n) > data_.size() - pos_) throw std::runtime_error("unexpected end of file");
    std::memcpy(c, data_.data() + pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return pos_ < data_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override {
    if (pos > data_.size()) throw std::runtime_error("seek past the end of the file");
    pos_ = static_cast<std::size_t>(pos);
  }

 private:
  const std::string& data_;
  std::size_t pos_ = 0;
};

// The channel names of the file's (first) part, in the header's order.
std::vector<std::string> channel_names(const Imf::Header& header) {
  std::vector<std::string> names;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) names.emplace_back(it.name());
  return names;
}

// A file of one channel, whatever its name, is a grey picture, read as the light itself: tools
// name a grey image's channel Y (OpenCV), A (tinyexr), R, L, V or gray; a lone R or G taken as
// coloured light would dim it to its Rec. 709 weight.
Image read_one_channel(Imf::InputFile& file, const std::string& path, const std::string& name) {
  const Imf::Channel& channel = *file.header().channels().findChannel(name);
  if (channel.xSampling != 1 || channel.ySampling != 1) {
    throw InputError(fmt::format("scene file '{}': its one channel '{}' is subsampled ({}x{}): give it a sample a pixel",
                                 path, name, channel.xSampling, channel.ySampling));
  }
  const Imath::Box2i window = file.header().dataWindow();
  const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
  check_scene_size(width, height, path);
  std::vector<float> values(static_cast<std::size_t>(width * height));
  Imf::FrameBuffer frame;
  char* const origin = reinterpret_cast<char*>(values.data() - window.min.x - window.min.y * width);
  frame.insert(name, Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * static_cast<std::size_t>(width)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  Image img;
  img.width = static_cast<int>(width);
  img.height = static_cast<int>(height);
  img.pixels.assign(values.begin(), values.end());
  return img;
}

Image read_rgb(const std::string& data, const std::string& path) {
  MemoryStream stream(data, path);
  Imf::RgbaInputFile file(stream);
  const Imath::Box2i window = file.dataWindow();
  const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
  const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
  check_scene_size(width, height, path);
  Imf::Array2D<Imf::Rgba> pixels(height, width);
  file.setFrameBuffer(&pixels[0][0] - window.min.x - window.min.y * width, 1, static_cast<std::size_t>(width));
  file.readPixels(window.min.y, window.max.y);
  Image img;
  img.width = static_cast<int>(width);
  img.height = static_cast<int>(height);
  img.pixels.resize(static_cast<std::size_t>(width * height));
  for (long long y = 0; y < height; ++y) {
    for (long long x = 0; x < width; ++x) {
      const Imf::Rgba& p = pixels[y][x];
      img.pixels[static_cast<std::size_t>(y * width + x)] =
          rec709_luminance(static_cast<float>(p.r), static_cast<float>(p.g), static_cast<float>(p.b));
    }
  }
  return img;
}

}  // namespace

Image decode_exr(const std::string& data, const std::string& path) {
  // OpenEXR checks every header against these before it allocates for the image (line offset
  // tables, buffers): a small file cannot make it ask for more than aesim would read.
  static const bool limited = [] {
    Imf::Header::setMaxImageSize(65535, 65535);
    Imf::Header::setMaxTileSize(4096, 4096);
    return true;
  }();
  (void)limited;
  try {
    // OpenEXR's RGBA interface fills a channel the file lacks with 0: a file with none of R, G, B
    // and Y (a layer's "left.R", a one-channel "L") would read as a black scene without a word.
    MemoryStream stream(data, path);
    Imf::InputFile file(stream);
    const std::vector<std::string> names = channel_names(file.header());
    const bool colour = std::any_of(names.begin(), names.end(),
                                    [](const std::string& n) { return n == "R" || n == "G" || n == "B" || n == "Y"; });
    Image img;
    if (names.size() == 1) {
      img = read_one_channel(file, path, names.front());
    } else if (colour) {
      img = read_rgb(data, path);
    } else {
      std::string list;
      for (std::size_t i = 0; i < names.size() && i < 8; ++i) list += (i == 0 ? "" : ", ") + names[i];
      if (names.size() > 8) list += fmt::format(" and {} more", names.size() - 8);
      throw InputError(fmt::format("scene file '{}': no R, G, B or Y channel to read light from (its channels: {}): "
                                   "give one layer's as R, G and B, e.g. oiiotool '{}' --ch L.R,L.G,L.B --chnames R,G,B "
                                   "-o rgb.exr for a layer L",
                                   path, names.empty() ? std::string("none") : list, path));
    }
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      const double v = img.pixels[i];
      if (!std::isfinite(v) || v < 0) {
        throw InputError(fmt::format("scene file '{}': pixel ({}, {}) has luminance {}: light is finite and not "
                                     "negative", path, i % static_cast<std::size_t>(img.width),
                                     i / static_cast<std::size_t>(img.width), v));
      }
    }
    return img;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string why = e.what();
    if (const std::size_t eol = why.find('\n'); eol != std::string::npos) why.resize(eol);
    throw InputError(fmt::format("scene file '{}': OpenEXR: {}", path, why));
  }
}

}  // namespace aesim
