#include "aesim/kernel/systemc_kernel.hpp"

#include <algorithm>
#include <atomic>

#include "aesim/errors/input_error.hpp"
#include "aesim/process/interrupt.hpp"

namespace aesim {
namespace {

std::atomic<std::uint64_t> kernels_made{0};

}  // namespace

std::uint64_t ScopedKernel::made() { return kernels_made.load(); }

ScopedKernel::ScopedKernel() : previous_(sc_core::sc_get_curr_simcontext()), mine_(new sc_core::sc_simcontext) {
  sc_core::sc_curr_simcontext = mine_;
  sc_core::sc_default_global_context = mine_;
  ++kernels_made;
  // A run with nothing to simulate (a dark scene ends at time zero) is not an error.
  sc_core::sc_report_handler::set_actions(sc_core::SC_ID_NO_SC_START_ACTIVITY_, sc_core::SC_DO_NOTHING);
}

ScopedKernel::~ScopedKernel() {
  sc_core::sc_curr_simcontext = previous_;
  sc_core::sc_default_global_context = previous_;
  delete mine_;
}

void run_until_starved(double duration) {
  const sc_core::sc_time slice(std::max(1e-3, duration / 100), sc_core::SC_SEC);
  do {
    // A slice stops at its last event (so the run ends where sc_start() would); when the next
    // activity lies beyond a slice, the slice reaches it, so every call makes progress.
    sc_core::sc_start(std::max(slice, sc_core::sc_time_to_pending_activity()), sc_core::SC_EXIT_ON_STARVATION);
    if (const int sig = interrupt_requested()) throw Interrupted(sig);
  } while (sc_core::sc_pending_activity());
}

}  // namespace aesim
