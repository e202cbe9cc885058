#include "aesim/scene/npy_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>
#include <half.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/scene/scene_file.hpp"

namespace aesim {
namespace {

// The longest header read before the file itself: NumPy pads its text to 64 bytes, a few hundred.
constexpr std::size_t kMaxNpyHeaderBytes = 1 << 16;

std::string what_of(const std::string& path) { return fmt::format("scene file '{}'", path); }

NpySceneLayout layout_of(const NpyHeader& header, const std::string& path) {
  const auto fail = [&](const std::string& why) { return InputError(fmt::format("scene file '{}': {}", path, why)); };
  NpySceneLayout l;
  l.header = header;
  const std::string& d = header.descr;
  if (!d.empty() && d.front() == '[') throw fail("a structured .npy array (an event file?) is not a scene: give an array of numbers");
  if (d.size() < 3 || (d[0] != '<' && d[0] != '>' && d[0] != '|' && d[0] != '=')) {
    throw fail(fmt::format("the .npy dtype '{}' is not one aesim reads", d));
  }
  l.kind = d[1];
  char* end = nullptr;
  const long bytes = std::strtol(d.c_str() + 2, &end, 10);
  if (*end != '\0' || bytes < 1 || bytes > 16) throw fail(fmt::format("the .npy dtype '{}' is not one aesim reads", d));
  l.item_bytes = static_cast<int>(bytes);
  l.big_endian = d[0] == '>';
  l.full_scale = array_full_scale(l.kind, l.item_bytes, what_of(path) + fmt::format(": dtype '{}'", d));

  const auto& shape = header.shape;
  if (shape.size() != 2 && shape.size() != 3) {
    throw fail(fmt::format("a {}-D array: a scene is 2-D (rows, columns) or 3-D (frames, rows, columns)", shape.size()));
  }
  check_not_colour_last(shape, what_of(path));
  const std::uint64_t frames = shape.size() == 3 ? shape[0] : 1;
  const std::uint64_t rows = shape[shape.size() - 2], cols = shape[shape.size() - 1];
  // Clamped first: a dimension past 2^40 is refused all the same, without overflowing the product.
  check_scene_size(static_cast<long long>(std::min<std::uint64_t>(cols, 1ULL << 40)),
                   static_cast<long long>(std::min<std::uint64_t>(rows, 1ULL << 40)), path);
  if (frames < 1 || frames > kMaxSceneFrames) {
    throw fail(fmt::format("{} frames: a scene has 1 to {}", frames, kMaxSceneFrames));
  }
  l.frames = static_cast<std::size_t>(frames);
  l.rows = static_cast<int>(rows);
  l.cols = static_cast<int>(cols);
  return l;
}

// Half-precision bits (IEEE 754 binary16) as a double, decoded by OpenEXR's Imath.
double half_to_double(std::uint16_t bits) {
  half h;
  h.setBits(bits);
  return static_cast<float>(h);
}

}  // namespace

void check_not_colour_last(const std::vector<std::uint64_t>& shape, const std::string& what) {
  if (shape.size() == 3 && (shape[2] == 3 || shape[2] == 4) && shape[0] > 4 && shape[1] > 4) {
    throw InputError(fmt::format("{}: a ({}, {}, {}) array reads as colour channels last (an RGB image): a scene is 2-D "
                                 "light (rows, columns) or 3-D frames (frames, rows, columns); give its linear luminance, "
                                 "0.2126 R + 0.7152 G + 0.0722 B",
                                 what, shape[0], shape[1], shape[2]));
  }
}

double array_full_scale(char kind, int item_bytes, const std::string& what) {
  if (kind == 'u' || kind == 'i') {
    if (item_bytes == 1) return 255.0;
    if (item_bytes == 2) return 65535.0;
    throw InputError(fmt::format("{}: integer arrays must be 8 or 16 bit (or give floats)", what));
  }
  if (kind == 'b' && item_bytes == 1) return 1.0;
  if (kind == 'f' && (item_bytes == 2 || item_bytes == 4 || item_bytes == 8)) return 1.0;
  throw InputError(fmt::format("{}: not an array of 8- or 16-bit integers, bools or 16-, 32- or 64-bit floats", what));
}

NpySceneLayout read_npy_scene_header(const std::string& path) {
  return layout_of(parse_npy_header(read_input_head(path, "scene file", kMaxNpyHeaderBytes), what_of(path)), path);
}

NpySceneLayout parse_npy_scene(const std::string& data, const std::string& path) {
  const NpySceneLayout l = layout_of(parse_npy_header(data, what_of(path)), path);
  const std::uint64_t values = static_cast<std::uint64_t>(l.frames) * l.rows * l.cols;
  const std::uint64_t have = (data.size() - l.header.data_offset) / static_cast<std::uint64_t>(l.item_bytes);
  if (have < values) {
    throw InputError(fmt::format("scene file '{}': truncated: {} values announced, {} there", path, values, have));
  }
  return l;
}

NpySceneFile open_npy_scene(const std::string& path) {
  NpySceneFile file;
  file.data = read_scene_file(path);
  file.layout = parse_npy_scene(file.data, path);
  return file;
}

Image npy_scene_frame(const NpySceneFile& file, std::size_t k, const std::string& path) {
  const NpySceneLayout& l = file.layout;
  if (k >= l.frames) throw std::out_of_range("npy_scene_frame: no such frame");
  Image img;
  img.width = l.cols;
  img.height = l.rows;
  img.pixels.resize(static_cast<std::size_t>(l.rows) * static_cast<std::size_t>(l.cols));
  const auto* base = reinterpret_cast<const unsigned char*>(file.data.data()) + l.header.data_offset;
  const std::size_t frames = l.frames, rows = static_cast<std::size_t>(l.rows), cols = static_cast<std::size_t>(l.cols);
  const double per_code = 1.0 / l.full_scale;  // as the Python module and the PGM reader scale codes
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < cols; ++c) {
      // Element (k, r, c): in C order the last index runs fastest, in Fortran order the first.
      const std::size_t index = l.header.fortran_order ? k + frames * (r + rows * c) : (k * rows + r) * cols + c;
      const unsigned char* p = base + index * static_cast<std::size_t>(l.item_bytes);
      std::uint64_t raw = 0;
      for (int b = 0; b < l.item_bytes; ++b) {
        const int shift = 8 * (l.big_endian ? l.item_bytes - 1 - b : b);
        raw |= std::uint64_t(p[b]) << shift;
      }
      double v = 0;
      if (l.kind == 'u') {
        v = static_cast<double>(raw);
      } else if (l.kind == 'i') {
        const std::uint64_t sign = std::uint64_t(1) << (8 * l.item_bytes - 1);
        v = static_cast<double>(static_cast<std::int64_t>((raw ^ sign) - sign));
      } else if (l.kind == 'b') {
        v = raw != 0 ? 1.0 : 0.0;
      } else if (l.item_bytes == 2) {
        v = half_to_double(static_cast<std::uint16_t>(raw));
      } else if (l.item_bytes == 4) {
        const auto bits = static_cast<std::uint32_t>(raw);
        float f;
        std::memcpy(&f, &bits, 4);
        v = f;
      } else {
        std::memcpy(&v, &raw, 8);
      }
      v *= per_code;
      if (!std::isfinite(v) || v < 0) {
        throw InputError(fmt::format("scene file '{}': {}row {}, column {} is {} (values must be finite and >= 0)", path,
                                     frames > 1 ? fmt::format("frame {}, ", k) : "", r, c, v));
      }
      img.pixels[r * cols + c] = v;
    }
  }
  return img;
}

}  // namespace aesim
