#include "aesim/process/interrupt.hpp"

#include <csignal>

namespace aesim {
namespace {

volatile std::sig_atomic_t g_interrupt = 0;

}  // namespace

void request_interrupt(int signal) { g_interrupt = signal; }
int interrupt_requested() { return g_interrupt; }
void clear_interrupt() { g_interrupt = 0; }

}  // namespace aesim
