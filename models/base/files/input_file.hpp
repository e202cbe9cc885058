#pragma once
#include <cstdint>
#include <string>

#include "aesim/limits/limits.hpp"

namespace aesim {

// A user's input file read whole: an InputError naming `what` and the path when it is missing or
// larger than `max_bytes` (checked before any memory is taken for it).
std::string read_input_file(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kMaxInputFileBytes);

}  // namespace aesim
