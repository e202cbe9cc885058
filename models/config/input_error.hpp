#pragma once
#include <stdexcept>
#include <string>

namespace aesim {

// Anything the user supplied that cannot be used: bad files, keys, values, options.
// The program reports what() on one line and exits with status 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace aesim
