#pragma once
#include <functional>
#include <string>

#include <fmt/format.h>

namespace aesim {

// A short hex identity of some text (a sweep's points, a receiver build's inputs), to tell one
// from another on this machine and library; not a cryptographic digest, and not meant to travel.
inline std::string content_hash_hex(const std::string& text) {
  return fmt::format("{:016x}", std::hash<std::string>{}(text));
}

}  // namespace aesim
