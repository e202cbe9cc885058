#include "aesim/scene/netpbm.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/scene/exr_image.hpp"
#include "aesim/scene/npy_scene.hpp"
#include "aesim/scene/photo_image.hpp"
#include "aesim/scene/tiff_image.hpp"
#include "aesim/scene/scene_file.hpp"

namespace aesim {
namespace {

constexpr long long kMaxSide = 1 << 16;

// Reads the whitespace- and comment-separated tokens of a Netpbm header.
class HeaderReader {
 public:
  HeaderReader(const std::string& data, const std::string& path) : data_(data), path_(path) {}

  std::string token() {
    skip_space_and_comments();
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (start == pos_) fail("truncated header");
    return data_.substr(start, pos_ - start);
  }

  // A plain PBM's pixel: one digit, with or without space before it.
  bool bit() {
    skip_space_and_comments();
    if (pos_ >= data_.size()) fail("truncated pixel data");
    const char c = data_[pos_++];
    if (c != '0' && c != '1') fail(fmt::format("malformed pixel '{}' (a PBM's are 0 or 1)", c));
    return c == '1';
  }

  long long integer(const char* what, long long lo, long long hi) {
    const std::string t = token();
    if (t.size() > 12 || t.find_first_not_of("0123456789") != std::string::npos) {
      fail(fmt::format("malformed {} '{}'", what, t));
    }
    const long long v = std::stoll(t);
    if (v < lo || v > hi) fail(fmt::format("{} {} out of range [{}, {}]", what, v, lo, hi));
    return v;
  }

  std::size_t remaining() const { return data_.size() - std::min(pos_, data_.size()); }

  // The single whitespace byte that ends a binary header.
  std::size_t data_start() {
    if (pos_ >= data_.size() || !std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      fail("missing whitespace before pixel data");
    }
    return pos_ + 1;
  }

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(fmt::format("scene file '{}': {}", path_, why));
  }

 private:
  void skip_space_and_comments() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (c == '#') {
        while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else {
        break;
      }
    }
  }

  const std::string& data_;
  const std::string& path_;
  std::size_t pos_ = 0;
};

// Reads width and height into `img` after the magic number, which names the format.
void read_size(HeaderReader& header, Image& img) {
  header.token();
  img.width = static_cast<int>(header.integer("width", 1, kMaxSide));
  img.height = static_cast<int>(header.integer("height", 1, kMaxSide));
  if (static_cast<long long>(img.width) * img.height > kMaxArrayPixels) {
    header.fail(fmt::format("{}x{} is more than the {} pixels aesim reads", img.width, img.height, kMaxArrayPixels));
  }
}

std::string magic_of(const std::string& data) { return data.size() >= 2 ? data.substr(0, 2) : std::string(); }

}  // namespace

Image read_pnm(const std::string& path) { return decode_pnm(read_scene_file(path), path); }
Image read_pfm(const std::string& path) { return decode_pfm(read_scene_file(path), path); }

namespace {

// The `count` samples of a PGM or PPM after its magic, width and height (one a pixel for grey,
// red, green and blue for colour), each value / maxval; ASCII for P2 and P3, binary (8 or 16 bit,
// big-endian) for P5 and P6.
std::vector<double> read_samples(HeaderReader& header, const std::string& data, bool binary, std::size_t count) {
  const long long maxval = header.integer("maxval", 1, 65535);
  const double scale = 1.0 / static_cast<double>(maxval);
  std::vector<double> samples(count);
  if (binary) {
    const std::size_t start = header.data_start();
    const std::size_t bytes_per = maxval > 255 ? 2 : 1;
    if (data.size() < start + count * bytes_per) {
      header.fail(fmt::format("truncated pixel data ({} of {} bytes)", data.size() - std::min(data.size(), start),
                              count * bytes_per));
    }
    const auto* p = reinterpret_cast<const unsigned char*>(data.data() + start);
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned v = bytes_per == 2 ? (unsigned(p[2 * i]) << 8) | p[2 * i + 1] : p[i];
      if (v > maxval) header.fail(fmt::format("sample {} value {} exceeds maxval {}", i, v, maxval));
      samples[i] = static_cast<double>(v) * scale;
    }
    return samples;
  }
  // Every ASCII sample takes a digit and a separator: a header cannot promise more than the file holds.
  if (header.remaining() + 1 < 2 * count) {
    header.fail(fmt::format("truncated pixel data (room for at most {} of {} values)", (header.remaining() + 1) / 2,
                            count));
  }
  for (std::size_t i = 0; i < count; ++i) samples[i] = static_cast<double>(header.integer("pixel value", 0, maxval)) * scale;
  return samples;
}

// A bitmap's samples: 1 is black (no light), 0 white (full scale). P1 writes a digit a pixel;
// P4 packs a row's pixels into bits, the first the most significant, each row from a new byte.
std::vector<double> read_bits(HeaderReader& header, const std::string& data, bool binary, const Image& img) {
  const std::size_t count = static_cast<std::size_t>(img.width) * img.height;
  std::vector<double> samples(count);
  if (!binary) {
    // Every pixel takes a digit: a header cannot promise more than the file holds.
    if (header.remaining() < count) {
      header.fail(fmt::format("truncated pixel data (room for at most {} of {} pixels)", header.remaining(), count));
    }
    for (double& v : samples) v = header.bit() ? 0.0 : 1.0;
    return samples;
  }
  const std::size_t start = header.data_start();
  const std::size_t row_bytes = (static_cast<std::size_t>(img.width) + 7) / 8;
  const std::size_t bytes = row_bytes * static_cast<std::size_t>(img.height);
  if (data.size() < start + bytes) {
    header.fail(fmt::format("truncated pixel data ({} of {} bytes)", data.size() - std::min(data.size(), start), bytes));
  }
  const auto* p = reinterpret_cast<const unsigned char*>(data.data() + start);
  for (std::size_t y = 0; y < static_cast<std::size_t>(img.height); ++y) {
    for (std::size_t x = 0; x < static_cast<std::size_t>(img.width); ++x) {
      const bool black = (p[y * row_bytes + x / 8] >> (7 - x % 8)) & 1u;
      samples[y * static_cast<std::size_t>(img.width) + x] = black ? 0.0 : 1.0;
    }
  }
  return samples;
}

}  // namespace

Image decode_pnm(const std::string& data, const std::string& path) {
  HeaderReader header(data, path);
  const std::string magic = magic_of(data);
  const bool bitmap = magic == "P1" || magic == "P4", grey = magic == "P2" || magic == "P5",
             colour = magic == "P3" || magic == "P6";
  if (!bitmap && !grey && !colour) {
    header.fail("not a Netpbm image (expected the magic number P1 to P6: PBM, PGM or PPM)");
  }
  const bool binary = magic == "P4" || magic == "P5" || magic == "P6";
  Image img;
  read_size(header, img);
  if (bitmap) {
    img.pixels = read_bits(header, data, binary, img);
    return img;
  }
  const std::size_t count = static_cast<std::size_t>(img.width) * img.height;
  if (grey) {
    img.pixels = read_samples(header, data, binary, count);
    return img;
  }
  const std::vector<double> rgb = read_samples(header, data, binary, 3 * count);
  img.pixels.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    img.pixels[i] = rec709_luminance(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
  }
  return img;
}

Image decode_pfm(const std::string& data, const std::string& path) {
  HeaderReader header(data, path);
  const std::string magic = magic_of(data);
  if (magic != "Pf" && magic != "PF") header.fail("not a PFM (expected Pf or PF)");
  Image img;
  read_size(header, img);
  const std::string scale_text = header.token();
  char* end = nullptr;
  const double scale = std::strtod(scale_text.c_str(), &end);
  if (*end != '\0' || scale == 0 || !std::isfinite(scale)) {
    header.fail(fmt::format("malformed scale '{}'", scale_text));
  }
  const bool little_endian = scale < 0;
  const int channels = magic == "PF" ? 3 : 1;
  const std::size_t count = static_cast<std::size_t>(img.width) * img.height;
  const std::size_t start = header.data_start();
  if (data.size() < start + count * channels * 4) {
    header.fail(fmt::format("truncated pixel data ({} of {} bytes)", data.size() - std::min(data.size(), start),
                            count * channels * 4));
  }
  img.pixels.resize(count);
  auto sample = [&](std::size_t index) {
    unsigned char b[4];
    std::memcpy(b, data.data() + start + 4 * index, 4);
    if (!little_endian) {
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
    }
    float v;
    std::memcpy(&v, b, 4);  // assumes a little-endian host, as every target of aesim is
    return v;
  };
  // PFM stores rows bottom to top.
  for (int row = 0; row < img.height; ++row) {
    const int y = img.height - 1 - row;
    for (int x = 0; x < img.width; ++x) {
      const std::size_t base = (static_cast<std::size_t>(row) * img.width + x) * channels;
      for (int c = 0; c < channels; ++c) {
        const double v = sample(base + static_cast<std::size_t>(c));
        if (!std::isfinite(v) || v < 0) {
          header.fail(fmt::format("pixel ({}, {}){} is {} (values must be finite and >= 0)", x, y,
                                  channels == 1 ? "" : fmt::format(" channel {}", c), v));
        }
      }
      const double v = channels == 1 ? double(sample(base)) : rec709_luminance(sample(base), sample(base + 1), sample(base + 2));
      img.pixels[static_cast<std::size_t>(y) * img.width + x] = v;
    }
  }
  return img;
}

bool is_scene_image(const std::string& path) {
  const std::string ext = file_extension(path);
  return std::any_of(kSceneImageExtensions.begin(), kSceneImageExtensions.end(),
                     [&ext](const char* e) { return ext == e; });
}

std::string scene_image_formats() {
  std::string text;
  for (std::size_t i = 0; i < kSceneImageExtensions.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == kSceneImageExtensions.size() ? " or " : ", ") + std::string(kSceneImageExtensions[i]);
  }
  return text;
}

Image read_image(const std::string& path) {
  const std::string ext = file_extension(path);
  // The magic number tells PBM, PGM and PPM apart, as Netpbm's own tools tell them, whichever of
  // their names the file has (imaging libraries write a grey picture as P5 under .ppm).
  if (ext == ".pgm" || ext == ".ppm" || ext == ".pnm" || ext == ".pbm") return read_pnm(path);
  if (ext == ".pfm") return read_pfm(path);
  if (ext == ".png") return decode_png(read_scene_file(path), path);
  if (ext == ".jpg" || ext == ".jpeg") return decode_jpeg(read_scene_file(path), path);
  if (ext == ".tif" || ext == ".tiff") {
    // Read from the file as libtiff needs it, a strip at a time: a camera's 16-bit frame may be
    // larger than a scene file read whole (kMaxInputFileBytes); its pixels bound the work.
    read_input_head(path, "scene file", 8);
    const std::vector<std::size_t> pages = tiff_file_pages(path);
    if (pages.size() != 1) {
      throw InputError(fmt::format("scene file '{}': a multi-page TIFF of {} frames is a scene of its own, not one frame "
                                   "of a folder",
                                   path, pages.size()));
    }
    return read_tiff_file(path, pages.front());
  }
  if (ext == ".exr") return decode_exr(read_scene_file(path), path);
  if (ext == ".npy") {
    const NpySceneFile file = open_npy_scene(path);
    if (file.layout.frames != 1) {
      throw InputError(fmt::format("scene file '{}': a 3-D array of {} frames is a scene of its own, not one frame of a folder",
                                   path, file.layout.frames));
    }
    return npy_scene_frame(file, 0, path);
  }
  // Common formats aesim does not decode, with the conversion that gives one it does.
  const std::string stem = std::filesystem::path(path).stem().string();
  std::string hint;
  for (const char* video : {".mp4", ".avi", ".mov", ".mkv", ".webm", ".m4v", ".mpg", ".mpeg"}) {
    if (ext == video) hint = fmt::format(": convert the video to Y4M, e.g. ffmpeg -i '{}' -pix_fmt gray '{}.y4m'", path, stem);
  }
  for (const char* image : {".gif", ".bmp", ".webp", ".heic", ".jxl"}) {
    if (ext == image) hint = ": convert the image to PNG or TIFF (a GIF's frames to numbered PNGs in a folder)";
  }
  throw InputError(fmt::format("scene file '{}': unsupported format (use {}, or a .y4m video){}", path,
                               scene_image_formats(), hint));
}

}  // namespace aesim
