#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace aesim {

// Transparent huge pages' size on x86-64 and most of aarch64's kernels.
inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

// Asks the kernel to back the whole 2 MiB pages inside [first, first + bytes) with huge pages when
// they are first touched (MADV_HUGEPAGE: honoured under THP mode "madvise", Debian's default, and
// "always"). Memory already touched keeps its pages. Only advice: nothing changes if it is refused.
inline void advise_huge_pages(void* first, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(first) + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(first) + bytes) & ~(kHugePageBytes - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)first;
  (void)bytes;
#endif
}

// Appends [first, first + count) to `v`, growing it by doubling as insert() would, but with every
// new block of 4 MiB or more advised onto huge pages before anything is copied into it: a run that
// keeps tens of millions of records otherwise takes a page fault every 4 KiB it fills (under
// glibc's allocator, whose large blocks are fresh mappings), which on a virtual machine cost more
// than the records (docs/performance.md).
template <typename T>
void append_on_huge_pages(std::vector<T>& v, const T* first, std::size_t count) {
  if (v.capacity() - v.size() < count) {
    const std::size_t want = std::max(v.size() + count, 2 * v.capacity());
    if (want * sizeof(T) >= 2 * kHugePageBytes) {
      std::vector<T> grown;
      grown.reserve(want);
      advise_huge_pages(grown.data(), want * sizeof(T));
      grown.insert(grown.end(), v.begin(), v.end());
      v.swap(grown);
    }
  }
  v.insert(v.end(), first, first + count);
}

}  // namespace aesim
