#pragma once
#include <cstdint>
#include <systemc>

namespace aesim {

// The one place that touches SystemC's global simulation context.
//
// SystemC allows one elaboration and one sc_start run per context, so a process that runs many
// designs (a test, `aesim compare`, a sweep point run in-process) gives each its own context: a
// ScopedKernel installs a fresh one and, when it goes out of scope, deletes it and puts the
// previous one back. Every module of the design must be destroyed before the ScopedKernel (declare
// it first). The context that was current before the first ScopedKernel (SystemC's own, made on
// first use) is never deleted here: SystemC's static teardown at exit still reads it. Measured with
// valgrind on `aesim compare` (every rung, pixel_processes included): 265 KB in 354 blocks are
// still reachable at exit, SystemC's allocator pools and that context; nothing is lost.
class ScopedKernel {
 public:
  ScopedKernel();
  ~ScopedKernel();
  ScopedKernel(const ScopedKernel&) = delete;
  // How many kernels this process has set up: the rungs without SystemC must not add to it.
  static std::uint64_t made();
  ScopedKernel& operator=(const ScopedKernel&) = delete;

 private:
  sc_core::sc_simcontext* previous_;
  sc_core::sc_simcontext* mine_;
};

// Runs the current kernel until nothing is left to do, as sc_start() does (the same events in the
// same order, the same end time), but in slices of simulated time (1 ms, or a hundredth of
// `duration` if longer, or up to the next activity if that is further), so that a request to stop
// (interrupt_requested: Ctrl-C in the Python module) ends the run within a slice by throwing
// Interrupted.
void run_until_starved(double duration);

}  // namespace aesim
