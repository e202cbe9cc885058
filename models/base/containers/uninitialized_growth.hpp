#pragma once
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace aesim {

// An allocator whose vector grows by resize() without writing zeros: for buffers of trivial
// records that are written the moment room is made for them (a tile's window of records, 16 bytes
// an event), where value-initialising each one first cost a pass over the memory (libstdc++'s
// _M_default_append, 1-2 % of a run writing .aedat4).
template <typename T>
class UninitializedGrowth : public std::allocator<T> {
  static_assert(std::is_trivially_default_constructible_v<T>, "left unwritten only where that is no state at all");

 public:
  template <typename U>
  struct rebind {
    using other = UninitializedGrowth<U>;
  };
  UninitializedGrowth() noexcept = default;
  template <typename U>
  UninitializedGrowth(const UninitializedGrowth<U>&) noexcept {}

  // Default-initialised: nothing written. Constructions with arguments (push_back, insert) go by
  // std::allocator_traits, which places them as usual.
  template <typename U>
  void construct(U* at) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(at)) U;
  }
};

template <typename T>
using UninitializedGrowthVector = std::vector<T, UninitializedGrowth<T>>;

}  // namespace aesim
