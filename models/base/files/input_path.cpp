#include "aesim/files/input_path.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/text/ascii_case.hpp"

namespace aesim {
namespace fs = std::filesystem;
namespace {

fs::file_type kind_of(const std::string& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec && st.type() != fs::file_type::not_found) {
    throw InputError(fmt::format("{} '{}': {}", what, path, ec.message()));
  }
  return st.type();
}

}  // namespace

bool is_input_file(const std::string& path, const std::string& what) {
  return kind_of(path, what) == fs::file_type::regular;
}

bool is_input_folder(const std::string& path, const std::string& what) {
  return kind_of(path, what) == fs::file_type::directory;
}

std::string not_a_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  switch (st.type()) {
    case fs::file_type::not_found: return fs::is_symlink(path, ec) ? "is a link to nothing" : "not found";
    case fs::file_type::directory: return "is a folder, not a file";
    case fs::file_type::fifo: return "is a FIFO, not a file";
    case fs::file_type::character: return "is a character device, not a file";
    case fs::file_type::block: return "is a block device, not a file";
    case fs::file_type::socket: return "is a socket, not a file";
    case fs::file_type::regular: return "";
    default: return ec ? ec.message() : "is not a regular file";
  }
}

void require_input_file(const std::string& path, const std::string& what) {
  if (!is_input_file(path, what)) throw InputError(fmt::format("{} '{}': {}", what, path, not_a_file(path)));
  // A repository cloned without Git LFS holds, in place of each large file, a few lines naming it.
  std::ifstream in(path, std::ios::binary);
  char start[40] = {};
  in.read(start, sizeof start);
  static constexpr char kLfs[] = "version https://git-lfs.github.com/spec/";
  if (in.gcount() == static_cast<std::streamsize>(sizeof start) && std::memcmp(start, kLfs, sizeof start) == 0) {
    throw InputError(fmt::format("{} '{}': a Git LFS pointer, not the file itself (fetch it with 'git lfs pull')", what, path));
  }
}

std::string file_extension(const std::string& path) { return ascii_lower(fs::path(path).extension().string()); }

}  // namespace aesim
