#include "aesim/files/input_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"

namespace aesim {

std::string read_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
  require_input_file(path, what);
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > max_bytes) {
    throw InputError(fmt::format("{} '{}': {} bytes, more than the {} MiB aesim reads", what, path, size,
                                 max_bytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{} '{}' cannot be opened", what, path));
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string read_input_head(const std::string& path, const std::string& what, std::size_t bytes) {
  require_input_file(path, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{} '{}' cannot be opened", what, path));
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

}  // namespace aesim
