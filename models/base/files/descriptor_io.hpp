#pragma once
#include <cstddef>
#include <cstdint>
#include <sys/types.h>

namespace aesim {

// Reads and writes on a file descriptor that go on through short transfers and through signals
// (a run's SIGINT handler is installed without SA_RESTART, so any of them may return EINTR). The
// system's reason is returned, never thrown, for each caller words its own failure.

// Writes all `n` bytes: 0, or the errno that stopped it (EIO for a write that took nothing).
int write_fully(int fd, const void* data, std::size_t n);
// The same through pwrite, at `offset`: the descriptor's own position is left alone.
int write_fully_at(int fd, const void* data, std::size_t n, std::uint64_t offset);
// Reads until `n` bytes or the end of the file: how many it read, or -1 with errno set.
ssize_t read_fully(int fd, void* data, std::size_t n);

}  // namespace aesim
