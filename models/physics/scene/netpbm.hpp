#pragma once
#include <array>
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// PGM (P2 ASCII, P5 binary; 8 or 16 bit, value/maxval), PPM (P3, P6: the same samples, red,
// green and blue, taken as Rec. 709 luminance of linear values, as PGM's) and PFM (Pf grey, PF
// colour taken as Rec. 709 luminance; values as is). Throws InputError naming the file and the
// defect.
Image read_pgm(const std::string& path);
Image read_ppm(const std::string& path);
Image read_pfm(const std::string& path);
// The same from the file's bytes; `path` names it in messages.
Image decode_pgm(const std::string& data, const std::string& path);
Image decode_ppm(const std::string& data, const std::string& path);
Image decode_pfm(const std::string& data, const std::string& path);
// Chooses by extension, in any case: .pgm, .ppm, .pfm, .png, .jpg or .jpeg (scene/photo_image),
// .exr (scene/exr_image).
Image read_image(const std::string& path);
// The extensions read_image reads, in the order messages list them; whether a path has one (in
// any case); and the list in words (".pgm, .ppm, ... or .exr").
inline constexpr std::array<const char*, 10> kSceneImageExtensions = {".pgm", ".ppm", ".pfm", ".png", ".jpg",
                                                                      ".jpeg", ".tif", ".tiff", ".exr", ".npy"};
bool is_scene_image(const std::string& path);
std::string scene_image_formats();

}  // namespace aesim
