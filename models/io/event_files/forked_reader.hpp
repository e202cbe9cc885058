#pragma once
#include <functional>
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// Runs `read` (the events of the file at `path`, through a library that can crash on hostile input:
// HDF5 1.10, matio) in a forked copy of aesim (fork_isolated), which sends the recording back on a
// pipe: a crash costs the copy, never the caller, and is this file's InputError naming `library`.
// An InputError `read` throws comes back as it was.
PolarityRecording read_in_forked_copy(const std::string& path, const char* library,
                                      const std::function<PolarityRecording()>& read);

}  // namespace aesim
