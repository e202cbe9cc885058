#pragma once
#include <iosfwd>
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// Writes an image with values in [0, 1] as 8-bit grey: PGM (P5) for .pgm, PNG for .png (when
// built with libpng). Throws InputError for other extensions.
void write_image(std::ostream& out, const std::string& path_for_format, const Image& image);
// True when `path` names a format write_image supports in this build.
void check_image_path(const std::string& path);

}  // namespace aesim
