#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "aesim/scene/image.hpp"

namespace aesim {

// TIFF scenes (.tif, .tiff: scientific and machine-vision cameras, microscopes, image tools),
// decoded by libtiff (any compression it reads, strips or tiles, planes together or apart):
//  - grey (BlackIsZero, or WhiteIsZero inverted) or RGB, alpha and other extra samples ignored (4
//    samples a pixel at most), or a palette (its 16-bit colours);
//  - unsigned integers of 1, 2 or 4 bits (grey or a palette index) or 8, 16 or 32 bits, taken as
//    linear light over their full scale (as PGM
//    and PPM: a camera's raw values; a TIFF a photo tool wrote is usually gamma-encoded: convert
//    it to PNG, which is decoded with the sRGB curve), or 32- and 64-bit floats as they are (as
//    PFM and OpenEXR: 1.0 is full scale, brighter may exceed it; negative or non-finite refused);
//  - colour reduced to Rec. 709 luminance; turned as its Orientation tag says (as EXIF's);
//  - `page`: the file's directory to read (0, the first; a multi-page file's frames are the
//    directories tiff_pages lists).
// Read a band of rows at a time into a ReducedImage: a picture larger than aesim holds is averaged
// down in linear light as it is read. Other layouts (CMYK, YCbCr, Lab, signed samples, a packed
// sample beside another, ...) are refused; so is anything libtiff reports as broken. Throws
// InputError naming the file and the reason.
Image decode_tiff(const std::string& data, const std::string& path, std::size_t page = 0);
// The same from the file at `path`, read as libtiff needs it (no more than a strip or a row of
// tiles held at once), so a file larger than a scene file read whole is read too.
Image read_tiff_file(const std::string& path, std::size_t page = 0);

// The directories of a TIFF file that are images of their own, in order: a multi-page file's
// frames (a camera's or a microscope's stack). Reduced-resolution copies (a pyramid's levels, a
// preview) and transparency masks (NewSubfileType bits 0 and 2) are not. At most kMaxSceneFrames;
// throws InputError naming the file.
std::vector<std::size_t> tiff_pages(const std::string& data, const std::string& path);
// The same for the file at `path`, reading only its directories (what a scene needs to know
// before it reads its frames).
std::vector<std::size_t> tiff_file_pages(const std::string& path);

}  // namespace aesim
