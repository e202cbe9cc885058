#include "scene/scene_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "files/input_path.hpp"
#include "limits/limits.hpp"

namespace aesim {

std::string read_scene_file(const std::string& path) {
  if (!is_input_file(path, "scene file")) {
    throw InputError(fmt::format("scene file '{}' not found", path));
  }
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxInputFileBytes) {
    throw InputError(fmt::format("scene file '{}': {} bytes, more than the {} MiB aesim reads", path, size,
                                 kMaxInputFileBytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("scene file '{}' cannot be opened", path));
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void check_scene_size(long long width, long long height, const std::string& path) {
  if (width < 1 || height < 1 || width > 65535 || height > 65535 || width * height > kMaxArrayPixels) {
    throw InputError(fmt::format("scene file '{}': {}x{} is more than the {} pixels (sides up to 65535) aesim reads",
                                 path, width, height, kMaxArrayPixels));
  }
}

}  // namespace aesim
