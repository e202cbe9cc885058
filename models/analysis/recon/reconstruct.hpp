#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "aesim/events/address_event.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

enum class ReconMode { Histogram, Interval };

// Scales an image for viewing: the `percentile` of its lit (non-zero) pixels becomes 1, brighter
// ones are clipped to 1. A real recording's few hot pixels would otherwise leave the rest black.
void scale_to_percentile(Image& img, double percentile);

// Brightness images from events, normalised so the brightest pixel is 1.
//  - Histogram: events per pixel. Needs many events per pixel; unbiased by lost events only if
//    losses hit all pixels alike.
//  - Interval: 1 / (time between the last two events of each pixel). Needs just two events per
//    pixel, but a lost event between them halves that pixel's estimate, and timestamps quantised
//    to the receiver tick limit the brightest pixels. Pixels with fewer than two events are 0.
Image reconstruct(const std::vector<AddressEvent>& events, int width, int height, ReconMode mode);

// The Histogram image from events already counted per pixel (y * width + x), as a run counts them.
Image histogram_image(const std::vector<std::uint32_t>& counts, int width, int height);

// Which events to use: the first `count` events, or those within `window` seconds of the first.
std::vector<AddressEvent> first_events(const std::vector<AddressEvent>& events, std::size_t count);
std::vector<AddressEvent> first_window(const std::vector<AddressEvent>& events, double window);

}  // namespace aesim
