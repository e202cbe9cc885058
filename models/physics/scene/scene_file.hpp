#pragma once
#include <string>

namespace aesim {

// A scene file's bytes, refused (InputError naming the file) when it is missing or larger than
// kMaxInputFileBytes: every image decoder reads through here.
std::string read_scene_file(const std::string& path);

// Refuses an image larger than aesim reads (sides up to 65535, at most kMaxArrayPixels pixels),
// before any memory is taken for it.
void check_scene_size(long long width, long long height, const std::string& path);
bool scene_size_allowed(long long width, long long height);  // the same test, as a value

}  // namespace aesim
