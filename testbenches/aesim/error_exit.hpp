#pragma once
#include <functional>

namespace aesim {

// Runs a command and turns what it throws into the program's one-line message on stderr and its
// exit status (2 bad input, 1 failure, 128 + N interrupted by signal N): the `aesim` program's
// main, and a sweep point run in a forked child.
int with_error_exit(const std::function<int()>& command);

}  // namespace aesim
