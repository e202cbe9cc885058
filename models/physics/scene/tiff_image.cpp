#include "aesim/scene/tiff_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <half.h>
#include <tiffio.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/scene/exif_orientation.hpp"
#include "aesim/scene/reduced_image.hpp"
#include "aesim/scene/scene_file.hpp"

namespace aesim {
namespace {

// The file's bytes as libtiff reads them, and the first error it reported.
struct TiffSource {
  const std::string* data;
  toff_t pos = 0;
  std::string error;
};

tsize_t read_proc(thandle_t h, tdata_t buffer, tsize_t size) {
  auto* src = static_cast<TiffSource*>(h);
  const toff_t left = src->pos < src->data->size() ? src->data->size() - src->pos : 0;
  const auto n = static_cast<toff_t>(size) < left ? static_cast<toff_t>(size) : left;
  std::memcpy(buffer, src->data->data() + src->pos, n);
  src->pos += n;
  return static_cast<tsize_t>(n);
}
tsize_t write_proc(thandle_t, tdata_t, tsize_t) { return 0; }
toff_t seek_proc(thandle_t h, toff_t offset, int whence) {
  auto* src = static_cast<TiffSource*>(h);
  const toff_t base = whence == SEEK_CUR ? src->pos : whence == SEEK_END ? src->data->size() : 0;
  src->pos = base + offset;
  return src->pos;
}
int close_proc(thandle_t) { return 0; }
toff_t size_proc(thandle_t h) { return static_cast<TiffSource*>(h)->data->size(); }
int map_proc(thandle_t, tdata_t*, toff_t*) { return 0; }
void unmap_proc(thandle_t, tdata_t, toff_t) {}

int on_error(TIFF*, void* user, const char* module, const char* format, va_list args) {
  auto* src = static_cast<TiffSource*>(user);
  if (src->error.empty()) {
    char text[256];
    std::vsnprintf(text, sizeof text, format, args);
    src->error = module ? fmt::format("{}: {}", module, text) : std::string(text);
  }
  return 1;
}
int on_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
struct OptionsFree {
  void operator()(TIFFOpenOptions* o) const { TIFFOpenOptionsFree(o); }
};

// The image's layout, from its tags.
struct Layout {
  std::uint32_t width = 0, height = 0;
  std::uint16_t spp = 1, bps = 8, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_MINISBLACK;
  std::uint16_t planar = PLANARCONFIG_CONTIG, orientation = ORIENTATION_TOPLEFT;
  int colours = 1;  // samples that carry light: 1 (grey or palette index) or 3 (RGB)
};

// One sample as a value of full scale.
double sample_value(const unsigned char* p, const Layout& l) {
  if (l.format == SAMPLEFORMAT_IEEEFP) {
    if (l.bps == 16) {
      // IEEE half (an HDR photo tool's 16-bit float), decoded by OpenEXR's Imath.
      std::uint16_t bits;
      std::memcpy(&bits, p, sizeof bits);
      half h;
      h.setBits(bits);
      return static_cast<float>(h);
    }
    if (l.bps == 32) {
      float f;
      std::memcpy(&f, p, sizeof f);
      return f;
    }
    double d;
    std::memcpy(&d, p, sizeof d);
    return d;
  }
  switch (l.bps) {
    case 1:
    case 2:
    case 4: return *p / double((1u << l.bps) - 1u);  // unpacked by unpack_row
    case 8: return *p / 255.0;
    case 16: {
      std::uint16_t v;
      std::memcpy(&v, p, sizeof v);
      return v / 65535.0;
    }
    default: {
      std::uint32_t v;
      std::memcpy(&v, p, sizeof v);
      return v / 4294967295.0;
    }
  }
}

// `n` samples of `bps` bits (1, 2 or 4), packed from each byte's high bits down as TIFF stores
// them (FillOrder 1; libtiff reverses the other order itself), one a byte in `out`.
void unpack_row(const unsigned char* packed, unsigned char* out, std::size_t n, unsigned bps) {
  const unsigned per_byte = 8u / bps, mask = (1u << bps) - 1u;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned shift = 8u - bps * (1u + unsigned(i % per_byte));
    out[i] = static_cast<unsigned char>((packed[i / per_byte] >> shift) & mask);
  }
}

// The file opened by libtiff, its errors into `src`: on its bytes (`src.data`), or read from
// `path` as libtiff needs it (`src.data` null: only the parts asked for). Null when it is not a TIFF.
std::unique_ptr<TIFF, TiffCloser> open_tiff(const std::string& path, TiffSource& src) {
  std::unique_ptr<TIFFOpenOptions, OptionsFree> options(TIFFOpenOptionsAlloc());
  if (!options) throw std::bad_alloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options.get(), on_error, &src);
  TIFFOpenOptionsSetWarningHandlerExtR(options.get(), on_warning, &src);
  // No single allocation past what a scene may take: a header claiming a huge strip is refused.
  TIFFOpenOptionsSetMaxSingleMemAlloc(options.get(), static_cast<tmsize_t>(kMaxInputFileBytes));
  if (!src.data) return std::unique_ptr<TIFF, TiffCloser>(TIFFOpenExt(path.c_str(), "rm", options.get()));
  return std::unique_ptr<TIFF, TiffCloser>(TIFFClientOpenExt(path.c_str(), "rm", &src, read_proc, write_proc, seek_proc,
                                                             close_proc, size_proc, map_proc, unmap_proc, options.get()));
}

// tiff_pages, from the bytes in `src.data` or (null) the file at `path`.
std::vector<std::size_t> pages_of(const std::string& path, TiffSource& src) {
  const auto fail = [&](const std::string& why) { throw InputError(fmt::format("scene file '{}': TIFF: {}", path, why)); };
  const std::unique_ptr<TIFF, TiffCloser> tif = open_tiff(path, src);
  if (!tif) fail(src.error.empty() ? "not a TIFF file" : src.error);
  std::vector<std::size_t> pages;
  std::size_t directory = 0;
  do {
    std::uint32_t subfile = 0;
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SUBFILETYPE, &subfile);
    if ((subfile & (FILETYPE_REDUCEDIMAGE | FILETYPE_MASK)) == 0) pages.push_back(directory);
    if (pages.size() > kMaxSceneFrames) {
      fail(fmt::format("more than {} pages (the most frames a scene has)", kMaxSceneFrames));
    }
    ++directory;
  } while (TIFFReadDirectory(tif.get()));
  if (!src.error.empty()) fail(src.error);
  if (pages.empty()) fail("no full-resolution image (every page is a reduced copy or a mask)");
  return pages;
}

// decode_tiff, from the bytes in `src.data` or (null) the file at `path`.
Image decode_tiff_from(TiffSource& src, const std::string& path, std::size_t page) {
  const auto fail = [&](const std::string& why) { throw InputError(fmt::format("scene file '{}': TIFF: {}", path, why)); };
  const std::unique_ptr<TIFF, TiffCloser> tif = open_tiff(path, src);
  if (!tif) fail(src.error.empty() ? "not a TIFF file" : src.error);
  TIFF* t = tif.get();
  if (page > 0 && (page > std::numeric_limits<tdir_t>::max() || !TIFFSetDirectory(t, static_cast<tdir_t>(page)))) {
    fail(src.error.empty() ? fmt::format("no page {}", page) : src.error);
  }
  Layout l;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &l.width);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &l.height);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &l.spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &l.bps);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &l.format);
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &l.planar);
  TIFFGetFieldDefaulted(t, TIFFTAG_ORIENTATION, &l.orientation);
  if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &l.photometric)) fail("no PhotometricInterpretation tag");
  ReducedImage::check(l.width, l.height, path);
  // JPEG compression stores colour as YCbCr (what photo tools and scanners write by default):
  // libtiff's JPEG codec hands it back as RGB when asked, its rows then RGB's.
  std::uint16_t compression = COMPRESSION_NONE;
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
  if (l.photometric == PHOTOMETRIC_YCBCR && compression == COMPRESSION_JPEG &&
      TIFFSetField(t, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB)) {
    l.photometric = PHOTOMETRIC_RGB;
  }
  const bool grey = l.photometric == PHOTOMETRIC_MINISBLACK || l.photometric == PHOTOMETRIC_MINISWHITE;
  const bool palette = l.photometric == PHOTOMETRIC_PALETTE;
  l.colours = l.photometric == PHOTOMETRIC_RGB ? 3 : 1;
  if (!grey && !palette && l.photometric != PHOTOMETRIC_RGB) {
    const char* named = l.photometric == PHOTOMETRIC_SEPARATED ? "CMYK"
                        : l.photometric == PHOTOMETRIC_YCBCR  ? "YCbCr"
                        : l.photometric == PHOTOMETRIC_CIELAB || l.photometric == PHOTOMETRIC_ICCLAB || l.photometric == PHOTOMETRIC_ITULAB
                            ? "Lab"
                            : "another";
    fail(fmt::format("{} colour (photometric interpretation {}; aesim reads grey, RGB and palette images)", named, l.photometric));
  }
  // Bilevel and 2- or 4-bit images (a scanned chart, a mask, a fax-compressed page) are packed a
  // row at a time; their samples are unpacked to a byte each as they are read.
  const bool packed = l.bps == 1 || l.bps == 2 || l.bps == 4;
  const bool integer = l.format == SAMPLEFORMAT_UINT && (packed || l.bps == 8 || l.bps == 16 || l.bps == 32);
  const bool floating = l.format == SAMPLEFORMAT_IEEEFP && (l.bps == 16 || l.bps == 32 || l.bps == 64) && !palette;
  if (!integer && !floating) {
    fail(fmt::format("{}-bit {} samples (aesim reads unsigned 1, 2, 4, 8, 16 or 32 bits, or 16-, 32- or 64-bit floats)", l.bps,
                     l.format == SAMPLEFORMAT_INT      ? "signed"
                     : l.format == SAMPLEFORMAT_IEEEFP ? "float"
                     : l.format == SAMPLEFORMAT_UINT   ? "unsigned"
                                                       : "complex or unknown"));
  }
  if (palette && l.bps > 8) fail(fmt::format("a {}-bit palette (aesim reads palettes of up to 8 bits)", l.bps));
  // Samples past the colours are alpha or other extras (ExtraSamples), which carry no light: up to
  // four samples in all whether declared or not (grey and alpha, RGB and alpha), more when the
  // ExtraSamples tag declares them (RGB with alpha and depth); more undeclared would be bands of a
  // multispectral image, of which aesim would have to guess one.
  std::uint16_t extras = 0;
  const std::uint16_t* extra_kinds = nullptr;
  TIFFGetField(t, TIFFTAG_EXTRASAMPLES, &extras, &extra_kinds);
  if (l.spp < l.colours || (l.spp > 4 && l.spp != l.colours + extras)) {
    fail(fmt::format("{} samples a pixel, {} of them declared extra (aesim reads {} to 4, or the colours and their "
                     "declared extras)",
                     l.spp, extras, l.colours));
  }
  if (packed && l.spp != 1) fail(fmt::format("{} samples a pixel of {} bits (aesim reads one, grey or a palette index)", l.spp, l.bps));
  if (floating && l.photometric == PHOTOMETRIC_MINISWHITE) fail("float samples with white at zero");
  std::uint16_t *red = nullptr, *green = nullptr, *blue = nullptr;
  if (palette && !TIFFGetField(t, TIFFTAG_COLORMAP, &red, &green, &blue)) fail("a palette image without its colour map");

  // The picture a band of rows at a time (a strip's rows, or a row of tiles', of every plane), each
  // row then turned to light and handed on: a picture larger than aesim holds is averaged down as
  // it is read (ReducedImage), and no more than a band of its samples is held at once.
  const std::size_t bytes = packed ? 1 : l.bps / 8u;
  const std::size_t planes = l.planar == PLANARCONFIG_SEPARATE ? l.spp : 1, per_pixel = planes > 1 ? 1 : l.spp;
  // One row of one plane as stored: packed rows are their bits rounded up to a byte.
  const auto stored_row = [&](std::uint64_t pixels) {
    return packed ? (pixels * l.bps + 7) / 8 : pixels * per_pixel * bytes;
  };
  const std::size_t unpacked_row = std::size_t(l.width) * per_pixel * bytes;
  const tmsize_t line = TIFFScanlineSize(t);
  if (line <= 0 || static_cast<std::uint64_t>(line) != stored_row(l.width)) fail(src.error.empty() ? "malformed rows" : src.error);
  // A stored row (`n` pixels of it) into the band's unpacked samples.
  const auto place = [&](const unsigned char* from, unsigned char* to, std::size_t n) {
    if (packed) {
      unpack_row(from, to, n, l.bps);
    } else {
      std::memcpy(to, from, n * per_pixel * bytes);
    }
  };
  std::uint32_t band_rows = 0, tw = 0, th = 0;
  std::vector<unsigned char> piece;  // one tile or strip as read
  const bool tiled = TIFFIsTiled(t);
  if (tiled) {
    TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
    TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
    const tmsize_t tile_size = TIFFTileSize(t);
    if (tw == 0 || th == 0 || tile_size <= 0 || static_cast<std::uint64_t>(tile_size) != stored_row(tw) * th) {
      fail(src.error.empty() ? "malformed tiles" : src.error);
    }
    // A tile no larger than the image itself could need (a header may claim any tile size).
    if (static_cast<std::uint64_t>(tile_size) > std::uint64_t(kMaxInputFileBytes)) {
      fail(fmt::format("tiles of {}x{} pixels, larger than aesim reads", tw, th));
    }
    piece.resize(static_cast<std::size_t>(tile_size));
    band_rows = th;
  } else {
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &band_rows);
    band_rows = std::max<std::uint32_t>(1, std::min(band_rows, l.height));
    const tmsize_t strip_size = TIFFStripSize(t);
    if (strip_size <= 0 || static_cast<std::uint64_t>(strip_size) < stored_row(l.width) * band_rows) {
      fail(src.error.empty() ? "malformed strips" : src.error);
    }
    if (static_cast<std::uint64_t>(strip_size) > std::uint64_t(kMaxInputFileBytes)) {
      fail(fmt::format("strips of {} rows, larger than aesim reads", band_rows));
    }
    piece.resize(static_cast<std::size_t>(strip_size));
  }
  // A band held at once: at most what the largest image aesim holds whole once took (4096 x 4096
  // pixels of 4 samples of 8 bytes), whatever shape of tile or strip the header claims.
  if (std::uint64_t(planes) * band_rows * unpacked_row > 2 * std::uint64_t(kMaxInputFileBytes)) {
    fail(fmt::format("{} rows of {} pixels a {}, more than aesim holds at once", band_rows, l.width, tiled ? "tile" : "strip"));
  }
  ReducedImage image(l.width, l.height, path);
  std::vector<unsigned char> band;
  std::vector<double> light(l.width);
  for (std::uint32_t y0 = 0; y0 < l.height; y0 += band_rows) {
    const std::uint32_t rows = std::min(band_rows, l.height - y0);
    band.resize(planes * rows * unpacked_row);
    for (std::size_t p = 0; p < planes; ++p) {
      unsigned char* plane = &band[p * rows * unpacked_row];
      if (tiled) {
        for (std::uint32_t x0 = 0; x0 < l.width; x0 += tw) {
          if (TIFFReadTile(t, piece.data(), x0, y0, 0, static_cast<std::uint16_t>(p)) < 0) {
            fail(src.error.empty() ? "a tile does not read" : src.error);
          }
          for (std::uint32_t r = 0; r < rows; ++r) {
            place(&piece[r * stored_row(tw)], plane + r * unpacked_row + std::size_t(x0) * per_pixel * bytes,
                  std::min(x0 + tw, l.width) - x0);
          }
        }
      } else {
        const tstrip_t strip = TIFFComputeStrip(t, y0, static_cast<std::uint16_t>(p));
        const tmsize_t got = TIFFReadEncodedStrip(t, strip, piece.data(), static_cast<tmsize_t>(piece.size()));
        if (got < 0 || static_cast<std::uint64_t>(got) < stored_row(l.width) * rows) {
          fail(src.error.empty() ? "a strip does not read" : src.error);
        }
        for (std::uint32_t r = 0; r < rows; ++r) place(&piece[r * stored_row(l.width)], plane + r * unpacked_row, l.width);
      }
    }
    for (std::uint32_t r = 0; r < rows; ++r) {
      const auto sample_at = [&](std::size_t x, std::size_t s) -> const unsigned char* {
        return planes > 1 ? &band[((s * rows + r) * l.width + x) * bytes] : &band[r * unpacked_row + (x * l.spp + s) * bytes];
      };
      for (std::size_t x = 0; x < l.width; ++x) {
        double v;
        if (palette) {
          const unsigned index = *sample_at(x, 0);
          v = rec709_luminance(red[index] / 65535.0, green[index] / 65535.0, blue[index] / 65535.0);
        } else if (l.colours == 3) {
          v = rec709_luminance(sample_value(sample_at(x, 0), l), sample_value(sample_at(x, 1), l), sample_value(sample_at(x, 2), l));
        } else {
          v = sample_value(sample_at(x, 0), l);
          if (l.photometric == PHOTOMETRIC_MINISWHITE && integer) v = 1.0 - v;
        }
        if (!(v >= 0) || !std::isfinite(v)) {
          fail(fmt::format("pixel ({}, {}) is {} (values must be finite and not negative)", x, y0 + r, v));
        }
        light[x] = v;
      }
      image.add_row(light.data());
    }
  }
  Image img = image.take();
  apply_exif_orientation(img, l.orientation);
  return img;
}

}  // namespace

std::vector<std::size_t> tiff_pages(const std::string& data, const std::string& path) {
  TiffSource src{&data, 0, {}};
  return pages_of(path, src);
}

std::vector<std::size_t> tiff_file_pages(const std::string& path) {
  TiffSource src{nullptr, 0, {}};
  return pages_of(path, src);
}

Image decode_tiff(const std::string& data, const std::string& path, std::size_t page) {
  TiffSource src{&data, 0, {}};
  return decode_tiff_from(src, path, page);
}

Image read_tiff_file(const std::string& path, std::size_t page) {
  TiffSource src{nullptr, 0, {}};
  return decode_tiff_from(src, path, page);
}

}  // namespace aesim
