#pragma once

namespace aesim {

// A request to stop, recorded by a signal handler (async-signal-safe: one sig_atomic_t) and read
// by long loops that stop themselves (a sweep between points, the event rung between windows) by
// throwing Interrupted. Only a command that asked for cooperation (output/temp_files.hpp) or the
// Python module, which catches Ctrl-C for the duration of a call, ever sees it set.
void request_interrupt(int signal);
int interrupt_requested();  // the signal number, or 0
void clear_interrupt();

}  // namespace aesim
