#pragma once
#include <cstddef>

#include "aesim/scene/image.hpp"

namespace aesim {

// The Orientation tag (0x0112) of EXIF metadata, as cameras record how to turn their stored
// pixels for display: 1 (as stored) to 8 (EXIF 2.3, section 4.6.4 A; TIFF 6.0 Orientation). `tiff`
// is the TIFF structure EXIF holds (byte-order mark, 42, IFD0 offset): a JPEG's APP1 segment
// after its "Exif\0\0", or a PNG's eXIf chunk as it is. 1 when the tag is absent, or the
// structure or the tag's value is not what EXIF says (a broken tag leaves the image as stored,
// as viewers do). Reads within `size` bytes only.
int exif_orientation(const unsigned char* tiff, std::size_t size);

// `img` (stored rows, top-left first) turned as `orientation` says, so that its rows are what a
// viewer shows: 2 mirrors left and right, 3 turns it half round, 4 mirrors top and bottom, 5
// mirrors across the top-left to bottom-right diagonal, 6 turns it a quarter clockwise, 7 mirrors
// across the other diagonal, 8 turns it a quarter anticlockwise (5 to 8 swap width and height).
// Any other value leaves it as it is.
void apply_exif_orientation(Image& img, int orientation);

}  // namespace aesim
