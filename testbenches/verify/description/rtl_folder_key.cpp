#include "description/rtl_folder_key.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/scratch_text.hpp"

namespace aesim {

namespace fs = std::filesystem;

namespace {

// A folder a build reads this much of is not the RTL's own (a home folder given as an include
// folder, say): refused before it is read, rather than hashed for minutes.
constexpr std::uintmax_t kKeyMostBytes = std::uintmax_t(256) << 20;

bool is_verilog(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".v" || ext == ".sv" || ext == ".vh" || ext == ".svh" || ext == ".inc";
}

}  // namespace

void add_rtl_folder_to_key(std::string& key, const fs::path& dir, RtlFolderFiles which,
                           const std::function<std::string(const fs::path&)>& place, const std::string& role) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file(ec) && (which == RtlFolderFiles::All || is_verilog(e.path()))) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  key += "folder " + place(dir) + "\n";
  for (const fs::path& f : files) {
    const std::uintmax_t bytes = fs::file_size(f, ec);
    if (ec || key.size() + bytes > kKeyMostBytes) {
      throw InputError(fmt::format("{}: '{}' holds over 256 MiB that the RTL's build may read; keep the RTL's files in a "
                                   "folder of their own",
                                   role, dir.string()));
    }
    key += place(f) + "\n" + read_scratch_text(f) + "\n";
  }
}

}  // namespace aesim
