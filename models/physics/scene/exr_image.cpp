#include "aesim/scene/exr_image.hpp"

#include <cmath>
#include <cstring>
#include <exception>

#include <ImfArray.h>
#include <ImfHeader.h>
#include <ImfIO.h>
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
        const double v = rec709_luminance(static_cast<float>(p.r), static_cast<float>(p.g), static_cast<float>(p.b));
        if (!std::isfinite(v) || v < 0) {
          throw InputError(fmt::format("scene file '{}': pixel ({}, {}) has luminance {}: light is finite and not "
                                       "negative", path, x, y, v));
        }
        img.pixels[static_cast<std::size_t>(y * width + x)] = v;
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
