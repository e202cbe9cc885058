#pragma once
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// Photographs as scenes (docs/reference.md section 1): code values are decoded to linear light, colour is
// reduced to Rec. 709 / sRGB luminance (Y = 0.2126 R + 0.7152 G + 0.0722 B, in linear light), and
// the result is normalised to full scale (the brightest code, 255 or 65535, is 1).
//  - PNG: 8 or 16 bit; grey, RGB, palette, with or without alpha (alpha is ignored: the scene is
//    the light the colours stand for). Decoded with the sRGB curve, unless the file's gAMA chunk
//    states another exponent without an sRGB chunk: 1.0 means the codes are linear light already,
//    any other exponent g decodes as code^(1/g).
//  - JPEG: grey or colour (YCbCr, as libjpeg returns it in RGB), 8 bit, decoded with the sRGB
//    curve; CMYK is refused.
// Both are turned as their EXIF Orientation says (a JPEG's APP1 Exif segment, a PNG's eXIf chunk;
// exif_orientation.hpp), so that the scene is the picture a viewer shows: a camera held upright
// stores its pixels on their side and says so there.
// Rows are decoded one at a time into a ReducedImage: a picture larger than aesim holds is
// averaged down in linear light as it is read.
// Throws InputError naming the file and the decoder's reason.
Image decode_png(const std::string& data, const std::string& path);
Image decode_jpeg(const std::string& data, const std::string& path);

// The sRGB transfer function inverted: linear light of a code value in [0, 1].
double srgb_to_linear(double code);

}  // namespace aesim
