#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "aesim/limits/limits.hpp"

namespace aesim {

// A user's input file read whole: an InputError naming `what` and the path when it is missing or
// larger than `max_bytes` (checked before any memory is taken for it).
std::string read_input_file(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kMaxInputFileBytes);
// Its first `bytes` bytes (fewer when the file is shorter): a header read before the file, to know
// what it holds. The same errors for a missing or unreadable file.
std::string read_input_head(const std::string& path, const std::string& what, std::size_t bytes);

}  // namespace aesim
