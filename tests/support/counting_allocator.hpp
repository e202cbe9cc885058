#pragma once
#include <cstddef>

namespace aesim::testing {

// Bytes the program holds through operator new, and the most it has held since reset_peak(): the
// test program that links counting_allocator.cpp replaces the global operator new and delete.
std::size_t allocated_bytes();
std::size_t peak_allocated_bytes();
void reset_peak();

}  // namespace aesim::testing
