#pragma once
#include <stdexcept>
#include <string>

namespace aesim {

// Anything the user supplied that cannot be used: bad files, keys, values, options, and work
// beyond a stated limit. The program reports what() on one line and exits with status 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// The system would not take an output (a full disk, a vanished folder): reported on one line
// with the system's reason, exit status 1.
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& what) : std::runtime_error(what) {}
};

// A signal asked a cooperative command to stop; exit status 128 + signal.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal_number) : std::runtime_error("interrupted"), signal(signal_number) {}
  int signal;
};

}  // namespace aesim
