#include "aesim/files/data_dir.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace aesim {
namespace {

namespace fs = std::filesystem;

// An installed aesim keeps its data in PREFIX/share/aesim beside PREFIX/lib/libaesim.so and
// PREFIX/bin/aesim: found from wherever this code was loaded (the library, or the program that
// links it statically), never from a path compiled in.
std::string installed_data_dir() {
  std::error_code ec;
  std::vector<fs::path> objects;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&installed_data_dir), &info) != 0 && info.dli_fname != nullptr) {
    objects.emplace_back(info.dli_fname);
  }
  objects.emplace_back(fs::read_symlink("/proc/self/exe", ec));
  for (const fs::path& object : objects) {
    if (object.empty()) continue;
    const fs::path share = fs::weakly_canonical(object, ec).parent_path().parent_path() / "share" / "aesim";
    if (!ec && fs::is_directory(share / "models" / "sensors", ec)) return share.string();
  }
  return "";
}

}  // namespace

std::string data_dir() {
  if (const char* env = std::getenv("AESIM_DATA_DIR"); env != nullptr && *env != '\0') return env;
  static const std::string installed = installed_data_dir();
  return installed.empty() ? AESIM_SOURCE_DIR : installed;
}

std::string shipped_if_missing(const std::string& path) {
  std::error_code ec;
  const fs::path given(path);
  if (path.empty() || given.is_absolute() || fs::symlink_status(given, ec).type() != fs::file_type::not_found) return path;
  const fs::path shipped = fs::path(data_dir()) / given;
  return fs::exists(shipped, ec) ? shipped.string() : path;
}

}  // namespace aesim
