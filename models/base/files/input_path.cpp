#include "files/input_path.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "errors/input_error.hpp"

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

}  // namespace aesim
