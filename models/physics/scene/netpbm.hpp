#pragma once
#include <array>
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// Netpbm's PBM (P1 ASCII, P4 binary; 1 is black), PGM (P2, P5; 8 or 16 bit, value/maxval) and
// PPM (P3, P6: the same samples, red, green and blue, taken as Rec. 709 luminance of linear
// values, as PGM's), told apart by the magic number; and PFM (Pf grey, PF colour taken as Rec. 709
// luminance; values as is). Throws InputError naming the file and the defect.
Image read_pnm(const std::string& path);
Image read_pfm(const std::string& path);
// The same from the file's bytes; `path` names it in messages.
Image decode_pnm(const std::string& data, const std::string& path);
Image decode_pfm(const std::string& data, const std::string& path);
// Chooses by extension, in any case: .pgm, .ppm, .pnm, .pbm, .pfm, .png, .jpg or .jpeg
// (scene/photo_image), .tif or .tiff (scene/tiff_image), .exr (scene/exr_image), .npy.
Image read_image(const std::string& path);
// The extensions read_image reads, in the order messages list them; whether a path has one (in
// any case); and the list in words (".pgm, .ppm, ... or .exr").
inline constexpr std::array<const char*, 12> kSceneImageExtensions = {
    ".pgm", ".ppm", ".pnm", ".pbm", ".pfm", ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr", ".npy"};
bool is_scene_image(const std::string& path);
std::string scene_image_formats();

}  // namespace aesim
