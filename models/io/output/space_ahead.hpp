#pragma once
#include <cstdint>

namespace aesim {

// Disk space reserved ahead of a growing file's writes, past its end (fallocate with
// FALLOC_FL_KEEP_SIZE: the file's size stays what was written). On ext4 a write into reserved
// space skips the delayed allocation's bookkeeping of each page: writing 66 MB a megabyte at a
// time took 6.5-6.8 ms with space reserved against 10.8-11.1 ms without, and the .npy writer
// makes that system call on the merge's thread. Only for a file this process owns alone (a
// temporary): release() cuts the file to its size, which would cut another writer's bytes.
// A reservation that fails (no space, a filesystem without fallocate, a quota) is not an error:
// the writes that follow report a full disk as they would have, and no more is tried.
class SpaceAhead {
 public:
  // Before writing the bytes of `fd` up to offset `end`.
  void before_writing_to(int fd, std::uint64_t end);
  // Gives back what was reserved past the file's end; before the file is closed.
  void release(int fd);

 private:
  std::uint64_t reserved_ = 0;  // the offset reserved up to
  bool reserved_any_ = false, refused_ = false;
};

}  // namespace aesim
