#pragma once
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// OpenEXR (HDR) scenes: scene-referred linear light already, so values are taken as they are
// (1.0 is full scale, as in a PFM; brighter is brighter), colour reduced to Rec. 709 luminance
// (0.2126 R + 0.7152 G + 0.0722 B), luminance/chroma files through OpenEXR's own conversion,
// alpha ignored. The data window's size is checked before any pixel is read; a NaN, infinite or
// negative luminance (no light has one) is refused. Throws InputError naming the file and
// OpenEXR's reason.
Image decode_exr(const std::string& data, const std::string& path);

}  // namespace aesim
