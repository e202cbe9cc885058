#pragma once
#include "aesim/scene/image.hpp"

namespace aesim {

// Area-weighted resampling: each output pixel takes the mean of the scene over the area it
// covers, as a photodiode integrates the light falling on it. Upsampling by an integer factor
// replicates pixels exactly; downsampling averages; other ratios weight partial overlaps.
Image resample_area(const Image& in, int width, int height);

}  // namespace aesim
