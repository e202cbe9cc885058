// PNG, JPEG and OpenEXR scenes: code values decoded to linear light with the sRGB curve (or as the PNG's
// gAMA says), colour reduced to Rec. 709 luminance, against values computed by hand from the
// sRGB standard; OpenEXR taken as linear light; malformed and oversized files refused in one line;
// PNG and EXR frame folders; and `aesim run` on a PNG and an EXR.
#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <cstdio>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <jpeglib.h>
#include <png.h>
#include <tiffio.h>
#include <zlib.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/exif_orientation.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/photo_image.hpp"
#include "aesim/scene/reduced_image.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/scene/tiff_image.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

// sRGB code -> linear light, from IEC 61966-2-1 by hand (not through the code under test).
constexpr double kCode10 = 0.0030352698;   // 10/255/12.92
constexpr double kCode128 = 0.2158605001;  // ((128/255 + 0.055)/1.055)^2.4
constexpr double kCode200 = 0.5775804404;  // ((200/255 + 0.055)/1.055)^2.4

struct PngSpec {
  int width = 1, height = 1, color_type = PNG_COLOR_TYPE_GRAY, depth = 8;
  std::vector<unsigned char> bytes;  // rows packed, 16-bit big-endian as PNG stores them
  std::vector<png_color> palette;
  double gamma = 0;  // a gAMA chunk when > 0
  std::string exif;  // an eXIf chunk when not empty
  int interlace = PNG_INTERLACE_NONE;
};

void append(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}

std::string encode_png(const PngSpec& s) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_set_write_fn(png, &out, append, nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(s.width), static_cast<png_uint_32>(s.height), s.depth, s.color_type,
               s.interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!s.palette.empty()) png_set_PLTE(png, info, s.palette.data(), static_cast<int>(s.palette.size()));
  if (s.gamma > 0) png_set_gAMA(png, info, s.gamma);
  if (!s.exif.empty()) {
    png_set_eXIf_1(png, info, static_cast<png_uint_32>(s.exif.size()),
                   reinterpret_cast<png_bytep>(const_cast<char*>(s.exif.data())));
  }
  png_write_info(png, info);
  const std::size_t row = s.bytes.size() / static_cast<std::size_t>(s.height);
  const int passes = png_set_interlace_handling(png);  // Adam7 writes every row once a pass
  for (int pass = 0; pass < passes; ++pass) {
    for (int y = 0; y < s.height; ++y) png_write_row(png, s.bytes.data() + static_cast<std::size_t>(y) * row);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

// With `scans`, a progressive file written with that scan script (libjpeg's own rules apply);
// with `app1`, an APP1 segment of those bytes.
std::string encode_jpeg(int width, int height, int components, J_COLOR_SPACE space, const std::vector<unsigned char>& bytes,
                        const std::vector<jpeg_scan_info>* scans = nullptr, const std::string& app1 = "") {
  jpeg_compress_struct c;
  jpeg_error_mgr err;
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &buffer, &size);
  c.image_width = static_cast<JDIMENSION>(width);
  c.image_height = static_cast<JDIMENSION>(height);
  c.input_components = components;
  c.in_color_space = space;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 100, TRUE);
  if (scans) {
    c.scan_info = scans->data();
    c.num_scans = static_cast<int>(scans->size());
  }
  jpeg_start_compress(&c, TRUE);
  if (!app1.empty()) {
    jpeg_write_marker(&c, JPEG_APP0 + 1, reinterpret_cast<const JOCTET*>(app1.data()), static_cast<unsigned>(app1.size()));
  }
  while (c.next_scanline < c.image_height) {
    JSAMPROW row = const_cast<unsigned char*>(bytes.data()) + c.next_scanline * static_cast<std::size_t>(width) * components;
    jpeg_write_scanlines(&c, &row, 1);
  }
  jpeg_finish_compress(&c);
  std::string out(reinterpret_cast<char*>(buffer), size);
  jpeg_destroy_compress(&c);
  std::free(buffer);
  return out;
}

TEST(PhotoScene, GreyPngCodesDecodeWithTheSrgbCurve) {
  PngSpec s;
  s.width = 5;
  s.bytes = {0, 10, 128, 200, 255};
  const Image img = decode_png(encode_png(s), "grey.png");
  ASSERT_EQ(img.width, 5);
  EXPECT_DOUBLE_EQ(img.pixels[0], 0.0);
  EXPECT_NEAR(img.pixels[1], kCode10, 1e-9);
  EXPECT_NEAR(img.pixels[2], kCode128, 1e-9);
  EXPECT_NEAR(img.pixels[3], kCode200, 1e-9);
  EXPECT_DOUBLE_EQ(img.pixels[4], 1.0);
}

TEST(PhotoScene, SixteenBitPngUsesTheFullCodeRange) {
  PngSpec s;
  s.width = 2;
  s.depth = 16;
  s.bytes = {0xFF, 0xFF, 0x80, 0x00};  // 65535 and 32768
  const Image img = decode_png(encode_png(s), "deep.png");
  EXPECT_DOUBLE_EQ(img.pixels[0], 1.0);
  EXPECT_NEAR(img.pixels[1], 0.2140482, 1e-6);  // ((32768/65535 + 0.055)/1.055)^2.4
}

TEST(PhotoScene, ColourBecomesLinearLuminance) {
  PngSpec s;
  s.width = 4;
  s.color_type = PNG_COLOR_TYPE_RGB;
  s.bytes = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
  const Image img = decode_png(encode_png(s), "rgb.png");
  EXPECT_NEAR(img.pixels[0], 0.2126, 1e-12);
  EXPECT_NEAR(img.pixels[1], 0.7152, 1e-12);
  EXPECT_NEAR(img.pixels[2], 0.0722, 1e-12);
  EXPECT_NEAR(img.pixels[3], kCode128, 1e-9);  // grey: the weights sum to 1

  PngSpec alpha = s;  // alpha carries no light: ignored
  alpha.width = 1;
  alpha.color_type = PNG_COLOR_TYPE_RGB_ALPHA;
  alpha.bytes = {255, 255, 255, 0};
  EXPECT_DOUBLE_EQ(decode_png(encode_png(alpha), "rgba.png").pixels[0], 1.0);

  PngSpec palette;
  palette.width = 2;
  palette.color_type = PNG_COLOR_TYPE_PALETTE;
  palette.palette = {{0, 255, 0}, {128, 128, 128}};
  palette.bytes = {0, 1};
  const Image p = decode_png(encode_png(palette), "palette.png");
  EXPECT_NEAR(p.pixels[0], 0.7152, 1e-12);
  EXPECT_NEAR(p.pixels[1], kCode128, 1e-9);
}

TEST(PhotoScene, AGammaOfOneMeansLinearCodes) {
  PngSpec s;
  s.width = 2;
  s.bytes = {128, 255};
  s.gamma = 1.0;
  const Image linear = decode_png(encode_png(s), "linear.png");
  EXPECT_NEAR(linear.pixels[0], 128.0 / 255.0, 1e-12);
  s.gamma = 1 / 2.2;  // the usual tag of an sRGB-like file: the sRGB curve
  EXPECT_NEAR(decode_png(encode_png(s), "g22.png").pixels[0], kCode128, 1e-9);
}

TEST(PhotoScene, JpegDecodesWithinItsQuantisation) {
  const std::string grey = encode_jpeg(16, 16, 1, JCS_GRAYSCALE, std::vector<unsigned char>(256, 128));
  const Image g = decode_jpeg(grey, "grey.jpg");
  ASSERT_EQ(g.width, 16);
  for (double v : g.pixels) EXPECT_NEAR(v, kCode128, 0.0035);  // one code either side
  std::vector<unsigned char> red;
  for (int i = 0; i < 256; ++i) red.insert(red.end(), {255, 0, 0});
  const Image r = decode_jpeg(encode_jpeg(16, 16, 3, JCS_RGB, red), "red.jpg");
  for (double v : r.pixels) EXPECT_NEAR(v, 0.2126, 0.01);  // YCbCr rounding of a saturated colour
}

// A TIFF structure as EXIF holds it, IFD0 of one entry: Orientation (0x0112), SHORT, count 1,
// `value`; in Motorola (big-endian) or Intel byte order. Written byte by byte from TIFF 6.0.
std::string exif_tiff(int value, bool big_endian) {
  const auto v = static_cast<char>(value);
  if (big_endian) {
    return std::string("MM\0\x2A\0\0\0\x08" "\0\x01" "\x01\x12\0\x03\0\0\0\x01\0", 19) + v +
           std::string("\0\0" "\0\0\0\0", 6);
  }
  return std::string("II\x2A\0\x08\0\0\0" "\x01\0" "\x12\x01\x03\0\x01\0\0\0", 18) + v +
         std::string("\0\0\0" "\0\0\0\0", 7);
}

// Six 8x8 blocks, 3 across and 2 down, each of one grey code: A B C over D E F.
constexpr unsigned char kBlockCodes[6] = {20, 60, 100, 140, 180, 220};
std::vector<unsigned char> six_blocks() {
  std::vector<unsigned char> bytes(24 * 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 24; ++x) bytes[static_cast<std::size_t>(y) * 24 + x] = kBlockCodes[(y / 8) * 3 + x / 8];
  }
  return bytes;
}

// The blocks (indices into kBlockCodes) as a viewer shows them, row by row, for each EXIF
// orientation, from the tag's definition (EXIF 2.3, 4.6.4 A: where the stored 0th row and 0th
// column are shown): 1 as stored, 2 mirrored, 3 turned half round, 4 flipped, 5 transposed,
// 6 turned a quarter clockwise, 7 transversed, 8 a quarter anticlockwise.
const std::vector<std::vector<int>> kShownBlocks[9] = {
    {},
    {{0, 1, 2}, {3, 4, 5}},
    {{2, 1, 0}, {5, 4, 3}},
    {{5, 4, 3}, {2, 1, 0}},
    {{3, 4, 5}, {0, 1, 2}},
    {{0, 3}, {1, 4}, {2, 5}},
    {{3, 0}, {4, 1}, {5, 2}},
    {{5, 2}, {4, 1}, {3, 0}},
    {{2, 5}, {1, 4}, {0, 3}},
};

void expect_shown_as(const Image& img, int orientation, double tolerance) {
  const std::vector<std::vector<int>>& rows = kShownBlocks[orientation];
  ASSERT_EQ(img.height, 8 * static_cast<int>(rows.size())) << orientation;
  ASSERT_EQ(img.width, 8 * static_cast<int>(rows[0].size())) << orientation;
  for (std::size_t by = 0; by < rows.size(); ++by) {
    for (std::size_t bx = 0; bx < rows[by].size(); ++bx) {
      const double code = kBlockCodes[rows[by][bx]] / 255.0;
      const double linear = std::pow((code + 0.055) / 1.055, 2.4);
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
          ASSERT_NEAR(img.at(static_cast<int>(bx) * 8 + x, static_cast<int>(by) * 8 + y), linear, tolerance)
              << "orientation " << orientation << " block " << bx << "," << by;
        }
      }
    }
  }
}

TEST(PhotoScene, ExifOrientationTurnsTheSceneAsAViewerShowsIt) {
  for (int orientation = 1; orientation <= 8; ++orientation) {
    for (const bool big : {true, false}) {
      const std::string tiff = exif_tiff(orientation, big);
      EXPECT_EQ(exif_orientation(reinterpret_cast<const unsigned char*>(tiff.data()), tiff.size()), orientation);
      PngSpec png;
      png.width = 24;
      png.height = 16;
      png.bytes = six_blocks();
      png.exif = tiff;
      expect_shown_as(decode_png(encode_png(png), "turned.png"), orientation, 1e-12);
      // Flat 8x8 blocks at quality 100: within a code of what was written.
      const std::string jpeg = encode_jpeg(24, 16, 1, JCS_GRAYSCALE, six_blocks(), nullptr, "Exif" + std::string(2, '\0') + tiff);
      expect_shown_as(decode_jpeg(jpeg, "turned.jpg"), orientation, 0.005);
    }
  }
}

TEST(PhotoScene, ABrokenExifLeavesTheImageAsStored) {
  const std::string good = exif_tiff(6, true);
  std::vector<std::string> broken;
  // Cut anywhere before the entry's end (header 8 bytes, count 2, entry 12; the next IFD's
  // offset after it is not needed to read the tag).
  for (std::size_t n = 0; n < 22; ++n) broken.push_back(good.substr(0, n));
  std::string s = good;
  s[0] = 'X';  // no byte order
  broken.push_back(s);
  s = good;
  s[3] = 43;  // not 42
  broken.push_back(s);
  s = good;
  s[7] = 0x7F;  // IFD0 past the end
  broken.push_back(s);
  s = good;
  s[8] = s[9] = '\xFF';  // 65535 entries in 26 bytes, the one there another tag
  s[11] = 0x13;
  broken.push_back(s);
  s = good;
  s[13] = 4;  // LONG, not SHORT
  broken.push_back(s);
  s = good;
  s[19] = 9;  // no such orientation
  broken.push_back(s);
  for (const std::string& tiff : broken) {
    EXPECT_EQ(exif_orientation(reinterpret_cast<const unsigned char*>(tiff.data()), tiff.size()), 1) << tiff.size();
    const std::string jpeg = encode_jpeg(24, 16, 1, JCS_GRAYSCALE, six_blocks(), nullptr, "Exif" + std::string(2, '\0') + tiff);
    expect_shown_as(decode_jpeg(jpeg, "broken.jpg"), 1, 0.005);
  }
}

void expect_refused(const std::function<void()>& decode, const std::string& words) {
  try {
    decode();
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(words), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

// A TIFF written by libtiff itself: `samples` are the image's bytes in its layout (per pixel, or
// plane after plane with PLANARCONFIG_SEPARATE), in rows or in tiles of 16x16.
struct TiffSpec {
  std::uint32_t width = 2, height = 1;
  std::uint16_t spp = 1, bps = 8, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_MINISBLACK;
  std::uint16_t planar = PLANARCONFIG_CONTIG, orientation = ORIENTATION_TOPLEFT, compression = COMPRESSION_NONE;
  std::uint16_t fill_order = FILLORDER_MSB2LSB;
  bool tiled = false;
  std::vector<unsigned char> samples;
  std::vector<std::uint16_t> colormap;  // 3 x 256 for a palette
  // The ExtraSamples tag's kinds; unless given, one alpha for 2 or 4 samples, none otherwise.
  std::vector<std::uint16_t> extra_samples;
};

std::string encode_tiff(const TiffSpec& s, const std::filesystem::path& dir) {
  const std::string path = (dir / "w.tif").string();
  TIFF* t = TIFFOpen(path.c_str(), "w");
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, s.width);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, s.height);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, s.spp);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, s.bps);
  TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, s.format);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, s.photometric);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, s.planar);
  TIFFSetField(t, TIFFTAG_ORIENTATION, s.orientation);
  TIFFSetField(t, TIFFTAG_COMPRESSION, s.compression);
  TIFFSetField(t, TIFFTAG_FILLORDER, s.fill_order);
  if (!s.extra_samples.empty()) {
    TIFFSetField(t, TIFFTAG_EXTRASAMPLES, static_cast<std::uint16_t>(s.extra_samples.size()), s.extra_samples.data());
  } else if (s.spp == 2 || s.spp == 4) {
    const std::uint16_t extra = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(t, TIFFTAG_EXTRASAMPLES, 1, &extra);
  }
  if (!s.colormap.empty()) {
    TIFFSetField(t, TIFFTAG_COLORMAP, s.colormap.data(), s.colormap.data() + 256, s.colormap.data() + 512);
  }
  const std::size_t planes = s.planar == PLANARCONFIG_SEPARATE ? s.spp : 1;
  const std::size_t per_pixel = planes > 1 ? 1 : s.spp;
  // The bytes of `w` pixels' samples; below 8 bits a row's are packed and it ends on a byte.
  const auto span = [&](std::size_t w) { return (w * per_pixel * s.bps + 7) / 8; };
  std::vector<unsigned char> buffer = s.samples;  // libtiff's encoders may work in the row they are given
  if (s.tiled) {
    TIFFSetField(t, TIFFTAG_TILEWIDTH, 16u);
    TIFFSetField(t, TIFFTAG_TILELENGTH, 16u);
    std::vector<unsigned char> tile(16 * span(16));
    for (std::size_t p = 0; p < planes; ++p) {
      for (std::uint32_t y0 = 0; y0 < s.height; y0 += 16) {
        for (std::uint32_t x0 = 0; x0 < s.width; x0 += 16) {
          std::fill(tile.begin(), tile.end(), 0);
          for (std::uint32_t y = y0; y < std::min(y0 + 16, s.height); ++y) {
            const std::size_t from = (p * s.height + y) * span(s.width) + span(x0);
            std::memcpy(&tile[std::size_t(y - y0) * span(16)], &buffer[from], span(std::min(x0 + 16, s.width) - x0));
          }
          TIFFWriteTile(t, tile.data(), x0, y0, 0, static_cast<std::uint16_t>(p));
        }
      }
    }
  } else {
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 3u);
    for (std::size_t p = 0; p < planes; ++p) {
      for (std::uint32_t y = 0; y < s.height; ++y) {
        TIFFWriteScanline(t, &buffer[(p * s.height + y) * span(s.width)], y, static_cast<std::uint16_t>(p));
      }
    }
  }
  TIFFClose(t);
  return testing::slurp(path);
}

template <typename T>
std::vector<unsigned char> bytes_of(const std::vector<T>& values) {
  std::vector<unsigned char> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

class TiffScenes : public testing::TempDirTest {};

TEST_F(TiffScenes, IntegersAreLinearOverFullScaleFloatsAsTheyAreColourIsRec709Luminance) {
  TiffSpec grey;
  grey.samples = {0, 51};
  Image img = decode_tiff(encode_tiff(grey, dir_), "g.tif");
  ASSERT_EQ(img.width, 2);
  EXPECT_DOUBLE_EQ(img.pixels[1], 0.2);  // 51 / 255: linear, as PGM (not the sRGB curve)

  TiffSpec white_is_zero = grey;
  white_is_zero.photometric = PHOTOMETRIC_MINISWHITE;
  EXPECT_DOUBLE_EQ(decode_tiff(encode_tiff(white_is_zero, dir_), "w.tif").pixels[1], 0.8);

  TiffSpec deep = grey;
  deep.bps = 16;
  deep.samples = bytes_of(std::vector<std::uint16_t>{65535, 13107});
  EXPECT_DOUBLE_EQ(decode_tiff(encode_tiff(deep, dir_), "d.tif").pixels[1], 0.2);

  TiffSpec wide = grey;
  wide.bps = 32;
  wide.samples = bytes_of(std::vector<std::uint32_t>{0, 4294967295u});
  EXPECT_DOUBLE_EQ(decode_tiff(encode_tiff(wide, dir_), "u32.tif").pixels[1], 1.0);

  TiffSpec hdr = grey;
  hdr.bps = 32;
  hdr.format = SAMPLEFORMAT_IEEEFP;
  hdr.samples = bytes_of(std::vector<float>{0.25f, 20.0f});
  img = decode_tiff(encode_tiff(hdr, dir_), "f.tif");
  EXPECT_DOUBLE_EQ(img.pixels[0], 0.25);
  EXPECT_DOUBLE_EQ(img.pixels[1], 20.0);  // brighter than full scale, as in a PFM

  // IEEE half floats (binary16, by hand: 0x3400 = 2^-2, 0x4d00 = 1.25 x 2^4 = 20, 0x0001 = 2^-24,
  // the least subnormal, 0x7bff = 65504, the largest), as an HDR photo tool writes 16-bit floats.
  TiffSpec half_float = grey;
  half_float.width = 4;
  half_float.bps = 16;
  half_float.format = SAMPLEFORMAT_IEEEFP;
  half_float.samples = bytes_of(std::vector<std::uint16_t>{0x3400, 0x4d00, 0x0001, 0x7bff});
  img = decode_tiff(encode_tiff(half_float, dir_), "f16.tif");
  ASSERT_EQ(img.pixels.size(), 4u);
  EXPECT_DOUBLE_EQ(img.pixels[0], 0.25);
  EXPECT_DOUBLE_EQ(img.pixels[1], 20.0);
  EXPECT_DOUBLE_EQ(img.pixels[2], std::ldexp(1.0, -24));
  EXPECT_DOUBLE_EQ(img.pixels[3], 65504.0);

  TiffSpec rgba;
  rgba.width = 3;
  rgba.spp = 4;  // alpha carries no light
  rgba.photometric = PHOTOMETRIC_RGB;
  rgba.samples = {255, 0, 0, 7, 0, 255, 0, 7, 0, 0, 255, 7};
  img = decode_tiff(encode_tiff(rgba, dir_), "rgb.tif");
  EXPECT_NEAR(img.pixels[0], 0.2126, 1e-12);
  EXPECT_NEAR(img.pixels[1], 0.7152, 1e-12);
  EXPECT_NEAR(img.pixels[2], 0.0722, 1e-12);
  TiffSpec planes = rgba;  // the same, each colour a plane of its own
  planes.planar = PLANARCONFIG_SEPARATE;
  planes.samples = {255, 0, 0, 0, 255, 0, 0, 0, 255, 7, 7, 7};
  EXPECT_EQ(decode_tiff(encode_tiff(planes, dir_), "planes.tif").pixels, img.pixels);

  TiffSpec indexed;
  indexed.photometric = PHOTOMETRIC_PALETTE;
  indexed.samples = {1, 0};
  indexed.colormap.assign(768, 0);
  indexed.colormap[1] = 65535;        // red of entry 1
  indexed.colormap[512 + 0] = 65535;  // blue of entry 0
  img = decode_tiff(encode_tiff(indexed, dir_), "palette.tif");
  EXPECT_NEAR(img.pixels[0], 0.2126, 1e-12);
  EXPECT_NEAR(img.pixels[1], 0.0722, 1e-12);
}

TEST_F(TiffScenes, StripsTilesCompressionAndOrientationGiveTheSameImage) {
  // 40x20 16-bit grey, every pixel its own value, read from strips and from tiles (edge tiles
  // part empty), plain, LZW and Deflate; then stored turned a quarter clockwise's inverse with
  // Orientation 6 (shown turned a quarter clockwise), as EXIF's.
  TiffSpec s;
  s.width = 40;
  s.height = 20;
  s.bps = 16;
  std::vector<std::uint16_t> values(800);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<std::uint16_t>(i * 80);
  s.samples = bytes_of(values);
  for (const bool tiled : {false, true}) {
    for (const std::uint16_t compression : {COMPRESSION_NONE, COMPRESSION_LZW, COMPRESSION_ADOBE_DEFLATE}) {
      s.tiled = tiled;
      s.compression = compression;
      const Image img = decode_tiff(encode_tiff(s, dir_), "s.tif");
      ASSERT_EQ(img.width, 40);
      ASSERT_EQ(img.height, 20);
      for (int y = 0; y < 20; ++y) {
        for (int x = 0; x < 40; ++x) ASSERT_DOUBLE_EQ(img.at(x, y), (y * 40 + x) * 80 / 65535.0) << tiled << compression;
      }
    }
  }
  s.tiled = false;
  s.compression = COMPRESSION_NONE;
  s.orientation = ORIENTATION_RIGHTTOP;  // 6
  const Image turned = decode_tiff(encode_tiff(s, dir_), "turned.tif");
  ASSERT_EQ(turned.width, 20);
  ASSERT_EQ(turned.height, 40);
  // Shown a quarter clockwise: stored (x, y) at (19 - y, x).
  EXPECT_DOUBLE_EQ(turned.at(19, 0), 0.0);
  EXPECT_DOUBLE_EQ(turned.at(19 - 3, 7), (3 * 40 + 7) * 80 / 65535.0);
}

// Samples of 1, 2 and 4 bits packed from each byte's high bits, a row ending on a byte (TIFF 6.0,
// BitsPerSample and FillOrder): `values` packed here by hand, row by row.
std::vector<unsigned char> pack_rows(const std::vector<unsigned>& values, std::size_t width, unsigned bps) {
  const std::size_t row = (width * bps + 7) / 8;
  std::vector<unsigned char> out(values.size() / width * row, 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t bit = (i % width) * bps;
    out[i / width * row + bit / 8] |= static_cast<unsigned char>(values[i] << (8 - bps - bit % 8));
  }
  return out;
}

TEST_F(TiffScenes, BilevelAndFewBitImagesAreTheirSamplesOverFullScale) {
  // A scanned chart or a mask: 20x18 1-bit (each row 2.5 bytes, so every row ends in padding), a
  // checkerboard of 3x3 squares, stored plain, PackBits, fax Group 3 and Group 4, in strips and in
  // tiles, high bit first and low bit first; 0 white (fax's own MinIsWhite) and 0 black.
  TiffSpec bilevel;
  bilevel.width = 20;
  bilevel.height = 18;
  bilevel.bps = 1;
  bilevel.photometric = PHOTOMETRIC_MINISWHITE;
  std::vector<unsigned> ink(20 * 18);
  for (std::size_t i = 0; i < ink.size(); ++i) ink[i] = (i % 20 / 3 + i / 20 / 3) % 2;
  bilevel.samples = pack_rows(ink, 20, 1);
  for (const std::uint16_t compression : {COMPRESSION_NONE, COMPRESSION_PACKBITS, COMPRESSION_CCITTFAX3, COMPRESSION_CCITTFAX4}) {
    for (const bool tiled : {false, true}) {
      for (const std::uint16_t order : {FILLORDER_MSB2LSB, FILLORDER_LSB2MSB}) {
        bilevel.compression = compression;
        bilevel.tiled = tiled;
        bilevel.fill_order = order;
        const Image img = decode_tiff(encode_tiff(bilevel, dir_), "chart.tif");
        ASSERT_EQ(img.width, 20);
        ASSERT_EQ(img.height, 18);
        for (std::size_t i = 0; i < ink.size(); ++i) {
          ASSERT_EQ(img.pixels[i], ink[i] ? 0.0 : 1.0) << i << " compression " << compression << " tiled " << tiled << " order " << order;
        }
      }
    }
  }
  TiffSpec mask = bilevel;
  mask.photometric = PHOTOMETRIC_MINISBLACK;
  mask.compression = COMPRESSION_NONE;
  mask.tiled = false;
  mask.fill_order = FILLORDER_MSB2LSB;
  const Image lit = decode_tiff(encode_tiff(mask, dir_), "mask.tif");
  for (std::size_t i = 0; i < ink.size(); ++i) ASSERT_EQ(lit.pixels[i], ink[i] ? 1.0 : 0.0) << i;

  // 2-bit grey, 0..3 over full scale, and a 4-bit palette of 16 entries.
  TiffSpec two;
  two.width = 5;
  two.bps = 2;
  two.samples = pack_rows({0, 1, 2, 3, 1}, 5, 2);
  EXPECT_EQ(two.samples, (std::vector<unsigned char>{0x1B, 0x40}));  // 00 01 10 11 | 01 00 00 00
  const Image grey = decode_tiff(encode_tiff(two, dir_), "two.tif");
  ASSERT_EQ(grey.width, 5);
  EXPECT_EQ(grey.pixels, (std::vector<double>{0.0, 1 / 3.0, 2 / 3.0, 1.0, 1 / 3.0}));
  TiffSpec indexed;
  indexed.width = 3;
  indexed.bps = 4;
  indexed.photometric = PHOTOMETRIC_PALETTE;
  indexed.samples = pack_rows({15, 0, 1}, 3, 4);
  indexed.colormap.assign(768, 0);
  indexed.colormap[15] = 65535;        // entry 15 red
  indexed.colormap[256 + 1] = 65535;   // entry 1 green
  const Image colours = decode_tiff(encode_tiff(indexed, dir_), "palette4.tif");
  EXPECT_NEAR(colours.pixels[0], 0.2126, 1e-12);
  EXPECT_EQ(colours.pixels[1], 0.0);
  EXPECT_NEAR(colours.pixels[2], 0.7152, 1e-12);

  TiffSpec grey_alpha = two;  // a packed sample beside another: no layout aesim reads
  grey_alpha.spp = 2;
  grey_alpha.samples = pack_rows({0, 1, 2, 3, 1, 0, 0, 0, 0, 0}, 10, 2);
  expect_refused([&] { decode_tiff(encode_tiff(grey_alpha, dir_), "ga.tif"); }, "2 samples a pixel of 2 bits");
}

// A scientific camera's or a scanner's TIFF larger than aesim holds: averaged down in blocks as
// its strips are read, as a PNG or JPEG is (PhotoScene.PicturesLargerThanAnArray...).
TEST_F(TiffScenes, APictureLargerThanAnArrayIsAveragedDownAsItsStripsAreRead) {
  TiffSpec board;
  board.width = board.height = 4100;
  board.compression = COMPRESSION_LZW;
  board.samples.resize(std::size_t(4100) * 4100);
  for (std::size_t i = 0; i < board.samples.size(); ++i) board.samples[i] = ((i % 4100 + i / 4100) % 2) ? 255 : 0;
  const Image img = decode_tiff(encode_tiff(board, dir_), "board.tif");
  ASSERT_EQ(img.width, 2050);
  ASSERT_EQ(img.height, 2050);
  for (const double v : img.pixels) ASSERT_DOUBLE_EQ(v, 0.5);
  // Read from the file a strip at a time, as a scene's TIFF is: the same picture.
  EXPECT_EQ(read_tiff_file((dir_ / "w.tif").string()).pixels, img.pixels);
  // In 16x16 tiles, RGB with each colour a plane of its own: a row of tiles of every plane at a
  // time, the same picture.
  TiffSpec planes = board;
  planes.tiled = true;
  planes.spp = 3;
  planes.photometric = PHOTOMETRIC_RGB;
  planes.planar = PLANARCONFIG_SEPARATE;
  planes.samples.insert(planes.samples.end(), board.samples.begin(), board.samples.end());
  planes.samples.insert(planes.samples.end(), board.samples.begin(), board.samples.end());
  const Image tiled = decode_tiff(encode_tiff(planes, dir_), "planes.tif");
  ASSERT_EQ(tiled.width, 2050);
  for (const double v : tiled.pixels) ASSERT_NEAR(v, 0.5, 1e-15);
}

TEST_F(TiffScenes, OtherLayoutsAndBrokenFilesAreOneLineErrors) {
  TiffSpec cmyk;
  cmyk.spp = 4;
  cmyk.photometric = PHOTOMETRIC_SEPARATED;
  cmyk.samples.assign(8, 0);
  expect_refused([&] { decode_tiff(encode_tiff(cmyk, dir_), "cmyk.tif"); }, "CMYK");
  TiffSpec signed_samples;
  signed_samples.format = SAMPLEFORMAT_INT;
  signed_samples.samples = {0, 1};
  expect_refused([&] { decode_tiff(encode_tiff(signed_samples, dir_), "int.tif"); }, "8-bit signed samples");
  TiffSpec negative;
  negative.bps = 32;
  negative.format = SAMPLEFORMAT_IEEEFP;
  negative.samples = bytes_of(std::vector<float>{1.0f, -1.0f});
  expect_refused([&] { decode_tiff(encode_tiff(negative, dir_), "neg.tif"); }, "pixel (1, 0)");
  TiffSpec half_infinity;  // 0x7c00: a half's infinity
  half_infinity.bps = 16;
  half_infinity.format = SAMPLEFORMAT_IEEEFP;
  half_infinity.samples = bytes_of(std::vector<std::uint16_t>{0x3c00, 0x7c00});
  expect_refused([&] { decode_tiff(encode_tiff(half_infinity, dir_), "inf16.tif"); }, "pixel (1, 0) is inf");
  TiffSpec good;
  good.width = 40;
  good.height = 20;
  good.samples.assign(800, 9);
  const std::string file = encode_tiff(good, dir_);
  expect_refused([&] { decode_tiff(file.substr(0, 100), "cut.tif"); }, "TIFF");
  expect_refused([&] { decode_tiff("II*\0garbage", "junk.tif"); }, "TIFF");
  // A few bytes claiming 65520x65520-pixel tiles (4 GB each): refused before any is taken. The
  // header written byte by byte from TIFF 6.0: little-endian, one IFD of ten entries.
  std::string huge = std::string("II*\0\x08\0\0\0", 8);
  const auto put = [&](std::uint64_t v, int n) {
    for (int b = 0; b < n; ++b) huge += static_cast<char>((v >> (8 * b)) & 0xFF);
  };
  put(10, 2);
  const std::uint32_t entries[][3] = {{256, 4, 4096}, {257, 4, 4096}, {258, 3, 8},     {259, 3, 1},     {262, 3, 1},
                                      {277, 3, 1},    {322, 4, 65520}, {323, 4, 65520}, {324, 4, 200}, {325, 4, 10}};
  for (const auto& e : entries) {
    put(e[0], 2);
    put(e[1], 2);
    put(1, 4);
    put(e[2], 4);
  }
  put(0, 4);
  huge += std::string(64, '\0');
  expect_refused([&] { decode_tiff(huge, "huge_tiles.tif"); }, "tiles of 65520x65520 pixels");
  expect_refused([&] { decode_tiff("", "empty.tif"); }, "TIFF");
}

// Samples past the colours that the ExtraSamples tag declares (alpha and a depth, as oiiotool
// writes RGBAZ) carry no light: the colours are read. Five samples none of them declared extra
// are a multispectral image's bands, which aesim does not guess among.
TEST_F(TiffScenes, DeclaredExtraSamplesAreLeftOutAndUndeclaredBandsRefused) {
  TiffSpec rgbaz;
  rgbaz.spp = 5;
  rgbaz.photometric = PHOTOMETRIC_RGB;
  rgbaz.extra_samples = {EXTRASAMPLE_UNASSALPHA, EXTRASAMPLE_UNSPECIFIED};
  rgbaz.samples = {255, 0, 0, 7, 9, 0, 0, 255, 7, 9};
  const Image img = decode_tiff(encode_tiff(rgbaz, dir_), "rgbaz.tif");
  ASSERT_EQ(img.pixels.size(), 2u);
  EXPECT_NEAR(img.pixels[0], 0.2126, 1e-12);
  EXPECT_NEAR(img.pixels[1], 0.0722, 1e-12);
  TiffSpec bands;
  bands.spp = 5;
  bands.samples.assign(10, 1);
  expect_refused([&] { decode_tiff(encode_tiff(bands, dir_), "bands.tif"); }, "5 samples a pixel, 0 of them declared extra");
}

// JPEG compression stores colour as YCbCr, subsampled 2x2, as photo tools and scanners write it
// (libtiff's own encoder here, given RGB rows): read back as RGB through libtiff's JPEG codec, a
// flat colour's luminance within JPEG's rounding.
TEST_F(TiffScenes, AJpegCompressedYCbCrTiffReadsAsItsRgb) {
  const std::string path = (dir_ / "ycbcr.tif").string();
  TIFF* t = TIFFOpen(path.c_str(), "w");
  TIFFSetField(t, TIFFTAG_IMAGEWIDTH, 32u);
  TIFFSetField(t, TIFFTAG_IMAGELENGTH, 16u);
  TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 3);
  TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
  TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_JPEG);
  TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_YCBCR);
  TIFFSetField(t, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB);
  TIFFSetField(t, TIFFTAG_JPEGQUALITY, 95);
  TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 16u);
  std::vector<unsigned char> row(32 * 3);
  for (std::size_t x = 0; x < 32; ++x) {
    row[3 * x] = 200;
    row[3 * x + 1] = 100;
    row[3 * x + 2] = 50;
  }
  for (std::uint32_t y = 0; y < 16; ++y) ASSERT_EQ(TIFFWriteScanline(t, row.data(), y, 0), 1);
  TIFFClose(t);
  const Image img = read_tiff_file(path, 0);
  ASSERT_EQ(img.width, 32);
  ASSERT_EQ(img.height, 16);
  const double expected = (0.2126 * 200 + 0.7152 * 100 + 0.0722 * 50) / 255;
  for (std::size_t i = 0; i < img.pixels.size(); ++i) EXPECT_NEAR(img.pixels[i], expected, 2.0 / 255) << i;
}

// A multi-page TIFF (a camera's or a microscope's stack) is a moving scene of its full-resolution
// pages, as a 3-D .npy is: page k is frame k, shown at scene.frame_rate. A reduced copy (a
// preview, NewSubfileType 1) is no frame. Written here page by page with libtiff.
TEST_F(TiffScenes, AMultiPageFileIsAMovingSceneOfItsFullResolutionPages) {
  constexpr std::uint32_t kWidth = 20, kHeight = 12;
  const auto page_value = [](int page, std::uint32_t x, std::uint32_t y) {
    return static_cast<unsigned char>(10 + (x * 7 + y * 3 + page * 50) % 200);
  };
  // Pages of kWidth x kHeight grey; `preview_after` > 0 puts a 4x4 reduced copy after that many.
  const auto write_stack = [&](const std::string& name, int pages, int preview_after, std::uint32_t last_width) {
    const std::string path = (dir_ / name).string();
    TIFF* t = TIFFOpen(path.c_str(), "w");
    for (int p = 0; p < pages; ++p) {
      if (p == preview_after) {
        TIFFSetField(t, TIFFTAG_SUBFILETYPE, FILETYPE_REDUCEDIMAGE);
        TIFFSetField(t, TIFFTAG_IMAGEWIDTH, 4u);
        TIFFSetField(t, TIFFTAG_IMAGELENGTH, 4u);
        TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
        TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
        TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
        const std::vector<unsigned char> row(4, 255);
        for (std::uint32_t y = 0; y < 4; ++y) TIFFWriteScanline(t, const_cast<unsigned char*>(row.data()), y, 0);
        TIFFWriteDirectory(t);
      }
      const std::uint32_t width = p + 1 == pages ? last_width : kWidth;
      TIFFSetField(t, TIFFTAG_IMAGEWIDTH, width);
      TIFFSetField(t, TIFFTAG_IMAGELENGTH, kHeight);
      TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
      TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
      TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
      std::vector<unsigned char> row(width);
      for (std::uint32_t y = 0; y < kHeight; ++y) {
        for (std::uint32_t x = 0; x < width; ++x) row[x] = page_value(p, x, y);
        TIFFWriteScanline(t, row.data(), y, 0);
      }
      TIFFWriteDirectory(t);
    }
    TIFFClose(t);
    return path;
  };
  const std::string stack = write_stack("stack.tif", 3, 1, kWidth);
  const SceneFiles files = find_scene(stack);
  EXPECT_EQ(files.tiff_pages, (std::vector<std::size_t>{0, 2, 3}));  // directory 1 is the preview
  const std::vector<Image> frames = read_frames(files);
  ASSERT_EQ(frames.size(), 3u);
  for (int p = 0; p < 3; ++p) {
    ASSERT_EQ(frames[p].width, static_cast<int>(kWidth)) << p;
    for (std::uint32_t y = 0; y < kHeight; ++y) {
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        ASSERT_DOUBLE_EQ(frames[p].at(x, y), page_value(p, x, y) / 255.0) << p << " " << x << " " << y;
      }
    }
  }
  // Run through: the same events, byte for byte, as the pages as a folder of frames.
  std::filesystem::create_directory(dir_ / "pages");
  for (int p = 0; p < 3; ++p) {
    std::string pgm = fmt::format("P5\n{} {}\n255\n", kWidth, kHeight);
    for (std::uint32_t y = 0; y < kHeight; ++y) {
      for (std::uint32_t x = 0; x < kWidth; ++x) pgm += static_cast<char>(page_value(p, x, y));
    }
    write(fmt::format("pages/{}.pgm", p), pgm);
  }
  const std::string common = " --set scene.frame_rate=50 --duration 100ms";
  const testing::Outcome from_stack = aesim("run --scene stack.tif --csv a.csv" + common);
  ASSERT_EQ(from_stack.status, 0) << from_stack.err;
  ASSERT_EQ(aesim("run --scene pages --csv b.csv" + common).status, 0);
  const std::string a = testing::slurp(dir_ / "a.csv");
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 200);
  EXPECT_EQ(a, testing::slurp(dir_ / "b.csv"));
  // One full-resolution page and a preview: a still scene of that page.
  const SceneFiles one = find_scene(write_stack("one.tif", 1, 0, kWidth));
  EXPECT_TRUE(one.tiff_pages.empty());
  const std::vector<Image> still = read_frames(one);
  ASSERT_EQ(still.size(), 1u);
  EXPECT_EQ(still[0].width, static_cast<int>(kWidth));
  // Pages of different sizes; a stack inside a folder of frames: one-line errors.
  expect_refused([&] { read_frames(find_scene(write_stack("mixed.tif", 2, -1, 16))); },
                 "mixed.tif frame 1' is 16x12, the first frame is 20x12");
  std::filesystem::copy_file(dir_ / "stack.tif", dir_ / "pages" / "3.tif");
  expect_refused([&] { read_frames(find_scene((dir_ / "pages").string())); },
                 "a multi-page TIFF of 3 frames is a scene of its own");
}

TEST(PhotoScene, MalformedAndOversizedFilesAreOneLineErrors) {
  PngSpec s;
  s.width = 64;
  s.height = 64;
  s.bytes.assign(64 * 64, 77);
  const std::string png = encode_png(s);
  expect_refused([&] { decode_png(png.substr(0, png.size() / 2), "cut.png"); }, "cut.png': PNG:");
  expect_refused([&] { decode_png("GIF89a....", "gif.png"); }, "not a PNG");
  expect_refused([&] { decode_jpeg("not a jpeg at all", "bad.jpg"); }, "bad.jpg': JPEG:");
  expect_refused([&] { decode_jpeg("", "empty.jpg"); }, "empty.jpg': JPEG:");
  // A header that asks for 70000 x 70000 pixels (CRC fixed): refused before any row is read.
  std::string huge = png;
  const std::size_t ihdr = huge.find("IHDR");
  for (int k = 0; k < 2; ++k) {
    const unsigned v = 70000;
    for (int b = 0; b < 4; ++b) huge[ihdr + 4 + 4 * k + b] = static_cast<char>(v >> (24 - 8 * b));
  }
  const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(huge.data() + ihdr), 17);
  for (int b = 0; b < 4; ++b) huge[ihdr + 17 + b] = static_cast<char>(crc >> (24 - 8 * b));
  expect_refused([&] { decode_png(huge, "huge.png"); }, "70000x70000 is more than");
  std::vector<unsigned char> cmyk(4 * 64, 9);
  expect_refused([&] { decode_jpeg(encode_jpeg(8, 8, 4, JCS_CMYK, cmyk), "cmyk.jpg"); }, "CMYK");
}

// An APNG (the PNG extension browsers play) declares its frames in an acTL chunk between IHDR and
// the first IDAT; decoders that do not know it show the default image alone. A scene of several
// frames is refused rather than simulated as its first; an APNG of one frame is that image.
TEST(PhotoScene, AnAnimatedPngIsRefusedRatherThanReadAsItsFirstFrame) {
  PngSpec s;
  s.width = 2;
  s.height = 2;
  s.bytes = {10, 128, 200, 255};
  const std::string still = encode_png(s);
  ASSERT_EQ(still.compare(12, 4, "IHDR"), 0);
  const auto with_actl = [&still](unsigned frames) {
    std::string chunk = std::string("\0\0\0\x08", 4) + "acTL";
    for (const unsigned v : {frames, 0u}) {
      for (int b = 0; b < 4; ++b) chunk += static_cast<char>(v >> (24 - 8 * b));
    }
    const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(chunk.data() + 4), 12);
    for (int b = 0; b < 4; ++b) chunk += static_cast<char>(crc >> (24 - 8 * b));
    return still.substr(0, 33) + chunk + still.substr(33);  // after the signature and IHDR
  };
  expect_refused([&] { decode_png(with_actl(3), "anim.png"); },
                 "anim.png': an animated PNG of 3 frames, of which aesim would read only the first");
  const Image one = decode_png(with_actl(1), "one_frame.png");
  ASSERT_EQ(one.pixels.size(), 4u);
  EXPECT_NEAR(one.pixels[0], kCode10, 1e-9);
  EXPECT_NEAR(one.pixels[1], kCode128, 1e-9);
  EXPECT_NEAR(one.pixels[2], kCode200, 1e-9);
  EXPECT_DOUBLE_EQ(one.pixels[3], 1.0);
}

// A picture larger than aesim holds (a 45-61 MP camera's, a 200 MP phone's) is averaged over k x k
// blocks in linear light as it is decoded, k the least that brings it within 2^24 pixels.
TEST(PhotoScene, PicturesLargerThanAnArrayAreAveragedDownInLinearLight) {
  // By hand: 65535 x 257 is over 2^24 pixels, 2 x 2 blocks bring it to 32768 x 129; the last
  // column of blocks holds one column and the last row one row. Light x + 1000 y.
  ReducedImage reduced(65535, 257, "wide.png");
  ASSERT_EQ(reduced.factor(), 2);
  std::vector<double> row(65535);
  for (int y = 0; y < 257; ++y) {
    for (int x = 0; x < 65535; ++x) row[x] = x + 1000.0 * y;
    reduced.add_row(row.data());
  }
  const Image small = reduced.take();
  ASSERT_EQ(small.width, 32768);
  ASSERT_EQ(small.height, 129);
  EXPECT_DOUBLE_EQ(small.at(0, 0), (0 + 1 + 1000 + 1001) / 4.0);
  EXPECT_DOUBLE_EQ(small.at(10, 3), 20.5 + 6500);  // x 20 and 21, y 6 and 7
  EXPECT_DOUBLE_EQ(small.at(32767, 0), (65534 + 66534) / 2.0);  // one column
  EXPECT_DOUBLE_EQ(small.at(5, 128), (10 + 11) / 2.0 + 256000);  // one row
  EXPECT_TRUE(ReducedImage::decodable(16384, 16384));  // 2^28
  EXPECT_FALSE(ReducedImage::decodable(16384, 16385));
  expect_refused([] { ReducedImage(65535, 65535, "huge.png"); }, "65535x65535 is more than the 268435456 pixels");

  // 4100 x 4100 (16.8 M pixels): 2050 x 2050. A checkerboard of black and white pixels is half the
  // light in every block (the codes' mean, 128, would decode to 0.216 in a PNG).
  const int side = 4100;
  std::vector<unsigned char> board(std::size_t(side) * side);
  for (std::size_t i = 0; i < board.size(); ++i) board[i] = ((i % side + i / side) % 2) ? 255 : 0;
  PngSpec png;
  png.width = png.height = side;
  png.bytes = board;
  const Image from_png = decode_png(encode_png(png), "board.png");
  ASSERT_EQ(from_png.width, 2050);
  ASSERT_EQ(from_png.height, 2050);
  for (const double v : from_png.pixels) ASSERT_DOUBLE_EQ(v, 0.5);
  // An interlaced PNG comes whole only after its last pass: read whole, so only up to 2^24 pixels.
  PngSpec interlaced = png;
  interlaced.interlace = PNG_INTERLACE_ADAM7;
  expect_refused([&] { decode_png(encode_png(interlaced), "adam7.png"); }, "an interlaced PNG of 4100x4100");
  interlaced.width = interlaced.height = 8;
  interlaced.bytes.resize(64);
  png.width = png.height = 8;
  png.bytes.resize(64);
  EXPECT_EQ(decode_png(encode_png(interlaced), "adam7.png").pixels, decode_png(encode_png(png), "plain.png").pixels);

  const std::vector<unsigned char> grey(std::size_t(side) * side, 128);
  const Image from_jpeg = decode_jpeg(encode_jpeg(side, side, 1, JCS_GRAYSCALE, grey), "grey.jpg");
  ASSERT_EQ(from_jpeg.width, 2050);
  ASSERT_EQ(from_jpeg.height, 2050);
  EXPECT_NEAR(from_jpeg.at(0, 0), kCode128, 1e-10);  // the constant's ten places
  EXPECT_NEAR(from_jpeg.at(2049, 1234), kCode128, 1e-10);
}

// A legal progressive JPEG of many scans: each AC coefficient of each of three components in a
// band of its own, refined bit by bit. Up to 1000 scans decode; past that the file is refused
// before the decoder spends its time on them (a 280 KB file of 20,000 scans once took 16 s).
std::vector<jpeg_scan_info> progressive_scans(int refinements) {
  std::vector<jpeg_scan_info> scans;
  jpeg_scan_info dc{};
  dc.comps_in_scan = 3;
  for (int k = 0; k < 3; ++k) dc.component_index[k] = k;
  scans.push_back(dc);  // DC of every component, full precision
  for (int comp = 0; comp < 3; ++comp) {
    for (int k = 1; k < 64; ++k) {
      jpeg_scan_info first{};
      first.comps_in_scan = 1;
      first.component_index[0] = comp;
      first.Ss = first.Se = k;
      first.Al = refinements;
      scans.push_back(first);
      for (int a = refinements; a > 0; --a) {
        jpeg_scan_info refine = first;
        refine.Ah = a;
        refine.Al = a - 1;
        scans.push_back(refine);
      }
    }
  }
  return scans;
}

TEST(PhotoScene, AProgressiveJpegOfTooManyScansIsRefused) {
  std::vector<unsigned char> rgb(16 * 16 * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<unsigned char>(i * 7);
  const std::vector<jpeg_scan_info> few = progressive_scans(3), many = progressive_scans(5);
  ASSERT_EQ(few.size(), 1u + 3 * 63 * 4);   // 757 scans: decoded
  ASSERT_EQ(many.size(), 1u + 3 * 63 * 6);  // 1135 scans: refused
  const Image ok = decode_jpeg(encode_jpeg(16, 16, 3, JCS_RGB, rgb, &few), "few.jpg");
  EXPECT_EQ(ok.width, 16);
  expect_refused([&] { decode_jpeg(encode_jpeg(16, 16, 3, JCS_RGB, rgb, &many), "many.jpg"); },
                 "more than 1000 scans");
}

class PhotoFiles : public testing::TempDirTest {};

TEST_F(PhotoFiles, PngFrameFoldersAndRunsWork) {
  PngSpec s;
  s.width = 32;
  s.height = 32;
  std::filesystem::create_directories(dir_ / "frames");
  for (int f = 0; f < 3; ++f) {
    s.bytes.assign(32 * 32, static_cast<unsigned char>(80 * f));
    write("frames/frame_" + std::to_string(f) + ".png", encode_png(s));
  }
  const SceneFiles files = find_scene((dir_ / "frames").string());
  ASSERT_EQ(files.frames.size(), 3u);
  const Image second = read_image(files.frames[1]);
  EXPECT_NEAR(second.pixels[0], 0.0802, 1e-4);  // code 80: ((80/255 + 0.055)/1.055)^2.4

  s.bytes.assign(32 * 32, 255);
  write("white.png", encode_png(s));
  const testing::Outcome o = aesim("run --scene white.png --duration 0.2 --summary s.json --set sim.fidelity=event");
  ASSERT_EQ(o.status, 0) << o.err;
  // Full scale everywhere on the 64x64 aloha array: every pixel at f_max (10 Hz) for 0.2 s.
  EXPECT_NE(testing::slurp(dir_ / "s.json").find("\"pixel_rate_max_hz\""), std::string::npos);
}

// An OpenEXR file written by OpenEXR's own writer (half floats: 0.25, 1 and 20 are exact).
void write_exr(const std::string& path, int width, int height, const std::vector<Imf::Rgba>& pixels,
               Imf::RgbaChannels channels = Imf::WRITE_RGBA) {
  Imf::RgbaOutputFile out(path.c_str(), width, height, channels);
  out.setFrameBuffer(pixels.data(), 1, static_cast<std::size_t>(width));
  out.writePixels(height);
}

TEST_F(PhotoFiles, OpenExrIsLinearLightAsItIs) {
  // Grey 0.25, an HDR 20 (twenty times full scale), pure red, pure green, pure blue, black.
  const std::vector<Imf::Rgba> px = {{0.25f, 0.25f, 0.25f, 1.0f}, {20.0f, 20.0f, 20.0f, 0.5f}, {1.0f, 0.0f, 0.0f, 1.0f},
                                     {0.0f, 1.0f, 0.0f, 0.0f},    {0.0f, 0.0f, 1.0f, 1.0f},    {0.0f, 0.0f, 0.0f, 1.0f}};
  write_exr((dir_ / "hdr.exr").string(), 3, 2, px);
  const Image img = read_image((dir_ / "hdr.exr").string());
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 2);
  const std::vector<double> expected = {0.25, 20.0, 0.2126, 0.7152, 0.0722, 0.0};  // Rec. 709, alpha ignored
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(img.pixels[i], expected[i], 1e-9) << i;
  // A luminance-only file: its Y as it is.
  write_exr((dir_ / "y.exr").string(), 2, 1, {{0.5f, 0.5f, 0.5f, 1.0f}, {4.0f, 4.0f, 4.0f, 1.0f}}, Imf::WRITE_Y);
  const Image y = read_image((dir_ / "y.exr").string());
  EXPECT_NEAR(y.pixels[0], 0.5, 1e-3);
  EXPECT_NEAR(y.pixels[1], 4.0, 4e-3);
  // Negative light, a truncated file and a foreign one are one-line errors naming the file.
  write_exr((dir_ / "neg.exr").string(), 1, 1, {{-1.0f, -1.0f, -1.0f, 1.0f}});
  const std::string whole = testing::slurp(dir_ / "hdr.exr");
  write("cut.exr", whole.substr(0, whole.size() / 2));
  write("text.exr", "not an exr file at all");
  for (const char* bad : {"neg.exr", "cut.exr", "text.exr"}) {
    try {
      read_image((dir_ / bad).string());
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(bad), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  // A folder of EXR frames, and a run on an EXR scene.
  std::filesystem::create_directories(dir_ / "frames");
  for (int f = 0; f < 2; ++f) {
    write_exr((dir_ / ("frames/f_" + std::to_string(f) + ".exr")).string(), 8, 8,
              std::vector<Imf::Rgba>(64, Imf::Rgba(0.5f * f, 0.5f * f, 0.5f * f, 1.0f)));
  }
  EXPECT_EQ(find_scene((dir_ / "frames").string()).frames.size(), 2u);
  const testing::Outcome o = aesim("run --scene hdr.exr --duration 0.1 --summary s.json");
  EXPECT_EQ(o.status, 0) << o.err;
}

// An OpenEXR file of float channels named as given, each its own values, by OpenEXR's own writer.
void write_exr_channels(const std::string& path, int width, int height,
                        const std::vector<std::pair<std::string, std::vector<float>>>& channels) {
  Imf::Header header(width, height);
  Imf::FrameBuffer frame;
  for (const auto& [name, values] : channels) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(values.data())),
                                  sizeof(float), sizeof(float) * static_cast<std::size_t>(width)));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(height);
}

// OpenEXR's RGBA interface fills the channels a file lacks with 0: without a look at the channels
// first, a grey picture in a channel named anything but Y, or a layer's channels, read as a black
// scene. A file of one channel is grey whatever the channel's name; channels with none of R, G, B
// and Y are refused, named.
TEST_F(PhotoFiles, AnExrOfOneChannelIsGreyWhateverItsNameAndLayersAreNamedNotReadAsDark) {
  for (const char* name : {"L", "A", "R", "G", "gray", "Y"}) {
    const std::string file = (dir_ / (std::string("one_") + name + ".exr")).string();
    write_exr_channels(file, 2, 1, {{name, {0.25f, 20.0f}}});
    const Image img = read_image(file);
    ASSERT_EQ(img.pixels.size(), 2u) << name;
    EXPECT_EQ(img.pixels[0], 0.25) << name;
    EXPECT_EQ(img.pixels[1], 20.0) << name;
  }
  // Two colour channels of three: the missing one is no light (Rec. 709 of R and G).
  write_exr_channels((dir_ / "rg.exr").string(), 1, 1, {{"R", {1.0f}}, {"G", {1.0f}}});
  EXPECT_NEAR(read_image((dir_ / "rg.exr").string()).pixels[0], 0.2126 + 0.7152, 1e-6);
  write_exr_channels((dir_ / "layer.exr").string(), 1, 1, {{"left.R", {1.0f}}, {"left.G", {1.0f}}, {"left.B", {1.0f}}});
  try {
    read_image((dir_ / "layer.exr").string());
    ADD_FAILURE() << "a layer's channels read as a scene";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no R, G, B or Y channel"), std::string::npos) << what;
    EXPECT_NE(what.find("left.B, left.G, left.R"), std::string::npos) << what;
    EXPECT_NE(what.find("--chnames R,G,B"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace aesim
