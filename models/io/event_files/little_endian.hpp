#pragma once
#include <cstddef>
#include <cstring>
#include <string>

namespace aesim {

// A little-endian number at byte `at` of a file's bytes (the caller has checked they are there).
// x86 and every platform aesim builds on are little-endian, as the formats that use it are.
template <typename T>
T little(const std::string& data, std::size_t at) {
  T v;
  std::memcpy(&v, data.data() + at, sizeof v);
  return v;
}

}  // namespace aesim
