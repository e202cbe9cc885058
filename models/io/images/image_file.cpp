#include "aesim/images/image_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <vector>

#include <fmt/format.h>
#include <png.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"

namespace aesim {
namespace {

std::vector<unsigned char> to_bytes(const Image& image) {
  std::vector<unsigned char> bytes(image.pixels.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<unsigned char>(std::lround(std::clamp(image.pixels[i], 0.0, 1.0) * 255.0));
  }
  return bytes;
}

void png_write_to_stream(png_structp png, png_bytep data, png_size_t length) {
  static_cast<std::ostream*>(png_get_io_ptr(png))->write(reinterpret_cast<const char*>(data),
                                                         static_cast<std::streamsize>(length));
}
void png_flush_stream(png_structp png) { static_cast<std::ostream*>(png_get_io_ptr(png))->flush(); }

void write_png(std::ostream& out, const Image& image) {
  const std::vector<unsigned char> bytes = to_bytes(image);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("PNG encoding failed");
  }
  png_set_write_fn(png, &out, png_write_to_stream, png_flush_stream);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, const_cast<png_bytep>(bytes.data() + static_cast<std::size_t>(y) * image.width));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

}  // namespace

void check_image_path(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext == ".pgm") return;
  if (ext == ".png") return;
  throw InputError(fmt::format("image '{}': unsupported format (use .pgm or .png)", path));
}

void write_image(std::ostream& out, const std::string& path_for_format, const Image& image) {
  check_image_path(path_for_format);
  if (file_extension(path_for_format) == ".png") {
    write_png(out, image);
    return;
  }
  const std::vector<unsigned char> bytes = to_bytes(image);
  out << "P5\n" << image.width << ' ' << image.height << "\n255\n";
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace aesim
