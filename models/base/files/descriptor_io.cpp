#include "aesim/files/descriptor_io.hpp"

#include <cerrno>
#include <unistd.h>

namespace aesim {
namespace {

template <typename Write>
int write_all(const void* data, std::size_t n, Write write) {
  const char* p = static_cast<const char*>(data);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t wrote = write(p + done, n - done, done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote < 0) return errno;
    if (wrote == 0) return EIO;
    done += static_cast<std::size_t>(wrote);
  }
  return 0;
}

}  // namespace

int write_fully(int fd, const void* data, std::size_t n) {
  return write_all(data, n, [fd](const char* p, std::size_t left, std::size_t) { return ::write(fd, p, left); });
}

int write_fully_at(int fd, const void* data, std::size_t n, std::uint64_t offset) {
  return write_all(data, n, [fd, offset](const char* p, std::size_t left, std::size_t done) {
    return ::pwrite(fd, p, left, static_cast<off_t>(offset + done));
  });
}

ssize_t read_fully(int fd, void* data, std::size_t n) {
  char* p = static_cast<char*>(data);
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::read(fd, p + done, n - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return -1;
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return static_cast<ssize_t>(done);
}

}  // namespace aesim
