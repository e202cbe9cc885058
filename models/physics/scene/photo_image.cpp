#include "aesim/scene/photo_image.hpp"

#include <csetjmp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <jpeglib.h>
#include <jerror.h>
#include <png.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/scene/exif_orientation.hpp"
#include "aesim/scene/reduced_image.hpp"
#include "aesim/scene/scene_file.hpp"

namespace aesim {
namespace {

// A decoding curve from code values (0..max) to linear light, as a table: at most 65,536 entries.
std::vector<double> decoding_table(unsigned max_code, double exponent /* 0: sRGB */) {
  std::vector<double> table(max_code + 1);
  for (unsigned c = 0; c <= max_code; ++c) {
    const double code = static_cast<double>(c) / max_code;
    table[c] = exponent > 0 ? std::pow(code, exponent) : srgb_to_linear(code);
  }
  return table;
}

// Linear-light luminance of a row of `n` pixels of 1 (grey) or 3 (RGB) channels of `T` codes.
template <typename T>
void row_luminance(const T* codes, std::size_t n, int channels, const std::vector<double>& table, double* light) {
  for (std::size_t i = 0; i < n; ++i) {
    if (channels == 1) {
      light[i] = table[codes[i]];
    } else {
      const T* p = &codes[3 * i];
      light[i] = rec709_luminance(table[p[0]], table[p[1]], table[p[2]]);
    }
  }
}

// A decoded row of 8- or 16-bit codes (16-bit in native order, copied out through `codes`) into
// the image being built.
void add_code_row(const unsigned char* row, std::size_t n, int channels, int depth, const std::vector<double>& table,
                  std::vector<std::uint16_t>& codes, std::vector<double>& light, ReducedImage& image) {
  if (depth == 16) {
    codes.resize(n * channels);
    std::memcpy(codes.data(), row, codes.size() * 2);
    row_luminance(codes.data(), n, channels, table, light.data());
  } else {
    row_luminance(row, n, channels, table, light.data());
  }
  image.add_row(light.data());
}

// libpng reports through these; `message` is the decoder's reason for the one-line error.
struct PngSource {
  const std::string* data;
  std::size_t pos;
  char message[256];
};

void png_read_from(png_structp png, png_bytep out, png_size_t length) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > src->data->size() - src->pos) png_error(png, "file ends early (truncated)");
  std::memcpy(out, src->data->data() + src->pos, length);
  src->pos += length;
}

void png_fail(png_structp png, png_const_charp message) {
  auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(src->message, sizeof src->message, "%s", message);
  png_longjmp(png, 1);
}

void png_ignore_warning(png_structp, png_const_charp) {}

// The JPEG counterpart: error_exit must not return, so it jumps back with libjpeg's message.
struct JpegErrors {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  int scans = 0;
};

// A progressive JPEG decodes every scan again: 20,000 scans of a small file cost seconds.
constexpr int kMaxJpegScans = 1000;

void jpeg_fail(j_common_ptr cinfo) {
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, errors->message);
  std::longjmp(errors->jump, 1);
}

// libjpeg's warnings are corrupt data it would paper over (a truncated file's missing rows are
// invented grey): each is an error here. Its trace of scan starts counts the scans.
void jpeg_message(j_common_ptr cinfo, int level) {
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  if (level < 0) jpeg_fail(cinfo);
  if (cinfo->err->msg_code == JTRC_SOS && ++errors->scans > kMaxJpegScans) {
    std::snprintf(errors->message, sizeof errors->message, "more than %d scans, the most aesim decodes", kMaxJpegScans);
    std::longjmp(errors->jump, 1);
  }
}

std::uint32_t big_endian_32(const std::string& data, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(data[at + k])); };
  return byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
}

// The frame count an animated PNG (APNG) declares in its acTL chunk, which comes before the first
// IDAT; 0 for a still PNG. libpng reads an APNG's default image alone, as any PNG decoder that
// does not know APNG shows it; a moving scene shown as its first frame would be a still scene.
std::uint32_t apng_frames(const std::string& data) {
  std::size_t at = 8;
  while (at + 12 <= data.size()) {
    const std::uint32_t length = big_endian_32(data, at);
    const std::string type = data.substr(at + 4, 4);
    if (type == "IDAT" || type == "IEND") return 0;
    if (type == "acTL") return length >= 8 && at + 16 <= data.size() ? big_endian_32(data, at + 8) : 0;
    // A chunk running past the end: libpng names the fault.
    if (length > data.size() - at - 12) return 0;
    at += 12 + length;
  }
  return 0;
}

}  // namespace

double srgb_to_linear(double code) {
  return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

Image decode_png(const std::string& data, const std::string& path) {
  if (data.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(data.data()), 0, 8) != 0) {
    throw InputError(fmt::format("scene file '{}': not a PNG (no PNG signature)", path));
  }
  if (const std::uint32_t frames = apng_frames(data); frames > 1) {
    throw InputError(fmt::format("scene file '{}': an animated PNG of {} frames, of which aesim would read only the first: "
                                 "give its frames as numbered PNGs in a folder (or a multi-page TIFF, a Y4M video)",
                                 path, frames));
  }
  PngSource src{&data, 0, {}};
  // Everything that owns memory is made before setjmp, so a longjmp out of libpng skips no
  // destructor.
  std::vector<unsigned char> bytes;
  std::vector<double> light, table;
  std::vector<std::uint16_t> codes;
  std::vector<png_bytep> rows;
  std::unique_ptr<ReducedImage> image;
  bool decodable = false, interlaced = false;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, png_fail, png_ignore_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::bad_alloc();
  }
  // Set between setjmp and a possible longjmp: volatile, so they hold what was stored.
  volatile int channels = 0, depth = 0, orientation = 1;
  volatile double exponent = 0;  // 0: sRGB
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw InputError(fmt::format("scene file '{}': PNG: {}", path, src.message));
  }
  png_set_read_fn(png, &src, png_read_from);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  decodable = ReducedImage::decodable(width, height);
  // An interlaced file's rows come whole only after its last pass: it is read whole, so only up to
  // the size of an image aesim holds.
  interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
  if (decodable && (!interlaced || scene_size_allowed(width, height))) {
    double gamma = 0;
    if (!png_get_valid(png, info, PNG_INFO_sRGB) && png_get_gAMA(png, info, &gamma) && gamma > 0 &&
        std::fabs(gamma - 1 / 2.2) > 0.01) {
      exponent = 1 / gamma;
    }
    png_set_expand(png);  // palette to RGB, grey below 8 bits to 8, transparency to alpha
    png_set_strip_alpha(png);
    if (png_get_bit_depth(png, info) == 16) png_set_swap(png);  // native byte order for uint16
    if (interlaced) png_set_interlace_handling(png);
    png_read_update_info(png, info);
    channels = png_get_channels(png, info);
    depth = png_get_bit_depth(png, info);
    if (channels == 1 || channels == 3) {
      const std::size_t row_bytes = png_get_rowbytes(png, info);
      image = std::make_unique<ReducedImage>(width, height, path);
      table = decoding_table(depth == 16 ? 65535 : 255, exponent);
      light.resize(width);
      if (interlaced) {
        rows.resize(height);
        bytes.resize(row_bytes * height);
        for (png_uint_32 y = 0; y < height; ++y) rows[y] = bytes.data() + y * row_bytes;
        png_read_image(png, rows.data());
        for (png_uint_32 y = 0; y < height; ++y) add_code_row(rows[y], width, channels, depth, table, codes, light, *image);
      } else {
        bytes.resize(row_bytes);
        for (png_uint_32 y = 0; y < height; ++y) {
          png_read_row(png, bytes.data(), nullptr);
          add_code_row(bytes.data(), width, channels, depth, table, codes, light, *image);
        }
      }
      // With the info: an eXIf chunk may come after the image data.
      png_read_end(png, info);
      png_uint_32 exif_size = 0;
      png_bytep exif = nullptr;
      if (png_get_eXIf_1(png, info, &exif_size, &exif) != 0) orientation = exif_orientation(exif, exif_size);
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  ReducedImage::check(width, height, path);
  if (interlaced && !scene_size_allowed(width, height)) {
    throw InputError(fmt::format("scene file '{}': an interlaced PNG of {}x{} (aesim averages down only PNGs saved "
                                 "without interlacing; interlaced ones up to {} pixels)",
                                 path, width, height, kMaxArrayPixels));
  }
  if (channels != 1 && channels != 3) {
    throw InputError(fmt::format("scene file '{}': PNG with {} channels after expansion", path, channels));
  }
  Image img = image->take();
  apply_exif_orientation(img, orientation);
  return img;
}

Image decode_jpeg(const std::string& data, const std::string& path) {
  jpeg_decompress_struct cinfo;
  JpegErrors errors;
  cinfo.err = jpeg_std_error(&errors.mgr);
  errors.mgr.error_exit = jpeg_fail;
  errors.mgr.emit_message = jpeg_message;
  errors.mgr.trace_level = 1;
  std::vector<unsigned char> row;
  std::vector<double> light;
  const std::vector<double> table = decoding_table(255, 0);
  std::unique_ptr<ReducedImage> image;
  // Set after the setjmp below and read after it returns normally: volatile, so that a register
  // copy a longjmp would leave stale is never what is read (GCC's -Wclobbered).
  volatile int orientation = 1;
  bool decodable = false;
  unsigned long width = 0, height = 0;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&cinfo);
    throw InputError(fmt::format("scene file '{}': JPEG: {}", path, errors.message));
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(data.data()), static_cast<unsigned long>(data.size()));
  jpeg_save_markers(&cinfo, JPEG_APP0 + 1, 0xFFFF);
  jpeg_read_header(&cinfo, TRUE);
  // A camera's EXIF (APP1, "Exif\0\0" then the TIFF structure) says how its pixels are turned.
  for (jpeg_saved_marker_ptr m = cinfo.marker_list; m != nullptr; m = m->next) {
    if (m->marker == JPEG_APP0 + 1 && m->data_length > 6 && std::memcmp(m->data, "Exif\0\0", 6) == 0) {
      orientation = exif_orientation(m->data + 6, m->data_length - 6);
      break;
    }
  }
  width = cinfo.image_width;
  height = cinfo.image_height;
  decodable = ReducedImage::decodable(static_cast<long long>(width), static_cast<long long>(height));
  const bool cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
  if (decodable && !cmyk) {
    cinfo.out_color_space = cinfo.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&cinfo);
    const int channels = cinfo.output_components;
    image = std::make_unique<ReducedImage>(static_cast<long long>(width), static_cast<long long>(height), path);
    row.resize(static_cast<std::size_t>(cinfo.output_width) * channels);
    light.resize(cinfo.output_width);
    while (cinfo.output_scanline < cinfo.output_height) {
      JSAMPROW at = row.data();
      jpeg_read_scanlines(&cinfo, &at, 1);
      row_luminance(row.data(), cinfo.output_width, channels, table, light.data());
      image->add_row(light.data());
    }
    jpeg_finish_decompress(&cinfo);
  }
  jpeg_destroy_decompress(&cinfo);
  if (cmyk) throw InputError(fmt::format("scene file '{}': CMYK JPEG (use a grey or RGB image)", path));
  ReducedImage::check(static_cast<long long>(width), static_cast<long long>(height), path);
  Image img = image->take();
  apply_exif_orientation(img, orientation);
  return img;
}

}  // namespace aesim
