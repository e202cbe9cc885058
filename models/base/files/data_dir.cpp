#include "aesim/files/data_dir.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace aesim {
namespace {

namespace fs = std::filesystem;

// An installed aesim keeps its data in PREFIX/share/aesim beside PREFIX/lib/libaesim.so,
// PREFIX/bin/aesim and PREFIX/lib/python3.X/dist-packages/aesim*.so: found from wherever this code
// was loaded (the library, or the program or Python module that links it statically), never from
// a path compiled in.
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
    const fs::path loaded = fs::weakly_canonical(object, ec);
    if (ec) continue;
    // PREFIX is the parent of a library's or program's folder (lib, bin), of the Python module's
    // folder's two parents' (lib/python3.X/dist-packages).
    fs::path folder = loaded.parent_path();
    for (int up = 0; up < 3 && folder.has_relative_path(); ++up, folder = folder.parent_path()) {
      const fs::path share = folder.parent_path() / "share" / "aesim";
      if (fs::is_directory(share / "models" / "sensors", ec)) return share.string();
    }
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
