#include "aesim/scene/scene_file.hpp"

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

std::string read_scene_file(const std::string& path) { return read_input_file(path, "scene file"); }

bool scene_size_allowed(long long width, long long height) {
  return width >= 1 && height >= 1 && width <= 65535 && height <= 65535 && width * height <= kMaxArrayPixels;
}

void check_scene_size(long long width, long long height, const std::string& path) {
  if (!scene_size_allowed(width, height)) {
    throw InputError(fmt::format("scene file '{}': {}x{} is more than the {} pixels (sides up to 65535) aesim reads",
                                 path, width, height, kMaxArrayPixels));
  }
}

}  // namespace aesim
