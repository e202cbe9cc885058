#pragma once
#include <string>

#include "aesim/process/interrupt.hpp"

namespace aesim {

// Temporary files and folders live beside their targets as `.NAME.aesim-tmp.HOST.PID`: hidden,
// recognisable, and naming the process that owns them. A SIGINT/SIGTERM/SIGHUP removes the
// temporary files this process registered; what a `kill -9` leaves, the next aesim command that
// writes into the same folder removes (its owner is gone), and never one of a live process or of
// another host that shares the folder.

// The temporary name for `target` owned by this process; `suffix` tells several apart.
std::string temp_name_for(const std::string& target, const std::string& suffix = "");

// The target a temporary name stands for (the path itself if it is no temporary name), for
// messages about what the user asked for.
std::string target_of(const std::string& path);
// "writing 'TARGET' failed: REASON", the system's reason (errno) as it stands now: called right
// after the failing write, it names a full disk as "No space left on device".
std::string write_failure(const std::string& path);

// Removes leftovers of dead aesim processes of this host in `folder` (no error if none).
void remove_stale_temps(const std::string& folder);

// Signal-safe registry of this process's temporary files: removed by the signal handlers.
void register_temp(const std::string& path);
void unregister_temp(const std::string& path);

// Installs the handlers (once, from main). A handler removes the registered files, then
// re-raises the signal with its default action, unless a long command asked to stop politely
// (below), in which case it only records the request.
void install_signal_cleanup();

// While a Cooperative object lives, a signal sets interrupt_requested() instead of ending the
// process, and blocking calls return EINTR: the command stops itself and unwinds its
// destructors (which remove its temporaries) and exits with 128 + the signal.
class Cooperative {
 public:
  Cooperative();
  ~Cooperative();
  Cooperative(const Cooperative&) = delete;
  Cooperative& operator=(const Cooperative&) = delete;
};

}  // namespace aesim
