#include "kernel/systemc_kernel.hpp"

#include <atomic>

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

}  // namespace aesim
