#pragma once
#include <optional>
#include <string>

#include "aesim/scene/image.hpp"

namespace aesim {

// Pixel behaviours that mimic feature-detecting imagers, applied to grey frames (values 0..1).
// Each returns a map whose value drives how often a pixel fires; `threshold` (0..1) zeroes
// everything at or below it.
enum class Behaviour { Intensity, Motion, Edge, Centroid };
Behaviour parse_behaviour(const std::string& name);  // throws InputError

// Grey-level clipping: values below `low` become 0 (the dark floor), values above `high` become `high`.
Image clip_levels(const Image& frame, double low, double high);
// The frame itself, thresholded.
Image intensity_map(const Image& frame, double threshold);
// |frame - previous|, thresholded: only what changed between consecutive frames.
Image motion_map(const Image& frame, const Image& previous, double threshold);
// Sobel gradient magnitude (borders replicated), scaled so a full black-to-white step is 1, thresholded.
Image edge_map(const Image& frame, double threshold);
// The centroid of the thresholded motion image (a single moving object), or nothing when no pixel moved.
std::optional<std::pair<double, double>> motion_centroid(const Image& frame, const Image& previous, double threshold);

}  // namespace aesim
