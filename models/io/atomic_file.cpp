#include "io/atomic_file.hpp"

#include <filesystem>
#include <system_error>

#include <fmt/format.h>
#include <unistd.h>

#include "config/input_error.hpp"

namespace aesim {
namespace fs = std::filesystem;

OutputFiles::~OutputFiles() {
  for (auto& f : files_) {
    if (f->temp.empty()) continue;
    f->stream.close();
    std::error_code ignored;
    fs::remove(f->temp, ignored);
  }
}

std::ostream& OutputFiles::open(const std::string& path) {
  auto f = std::make_unique<Pending>();
  f->target = path;
  f->temp = fmt::format("{}.tmp.{}", path, ::getpid());
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw InputError(fmt::format("cannot create folder '{}': {}", parent.string(), ec.message()));
  f->stream.open(f->temp, std::ios::binary | std::ios::trunc);
  if (!f->stream) throw InputError(fmt::format("cannot write '{}'", path));
  files_.push_back(std::move(f));
  return files_.back()->stream;
}

std::string OutputFiles::adopt(const std::string& path) {
  open(path).flush();
  files_.back()->stream.close();
  return files_.back()->temp;
}

void OutputFiles::commit() {
  for (auto& f : files_) {
    if (!f->stream.is_open()) continue;  // adopted: written and closed by its writer
    f->stream.flush();
    if (!f->stream) throw std::runtime_error(fmt::format("writing '{}' failed", f->target));
    f->stream.close();
  }
  for (auto& f : files_) {
    std::error_code ec;
    fs::rename(f->temp, f->target, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot rename into '{}': {}", f->target, ec.message()));
    f->temp.clear();
  }
}

}  // namespace aesim
