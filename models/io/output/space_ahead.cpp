#include "aesim/output/space_ahead.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace aesim {
namespace {

// Files that stay under a megabyte reserve nothing (two system calls more than they need); past
// it, 16 MiB at a time (reserving 4 or 64 MiB at a time took the same time for 66 MB).
constexpr std::uint64_t kFirst = std::uint64_t(1) << 20;
constexpr std::uint64_t kStep = std::uint64_t(16) << 20;

}  // namespace

void SpaceAhead::before_writing_to(int fd, std::uint64_t end) {
  if (refused_ || end <= reserved_ || end <= kFirst) return;
  const std::uint64_t from = reserved_, to = end + kStep;
  if (::fallocate(fd, FALLOC_FL_KEEP_SIZE, static_cast<off_t>(from), static_cast<off_t>(to - from)) != 0) {
    refused_ = true;
    // Whatever part it reserved lies past the end too, for release().
    reserved_any_ = true;
    return;
  }
  reserved_any_ = true;
  reserved_ = to;
}

void SpaceAhead::release(int fd) {
  if (!reserved_any_) return;
  reserved_any_ = false;
  struct stat s {};
  // A cut to the size the file has frees the blocks past it; the file's bytes stay as they are.
  if (::fstat(fd, &s) == 0) static_cast<void>(::ftruncate(fd, s.st_size));
}

}  // namespace aesim
