#pragma once
#include <functional>
#include <thread>

namespace aesim {

// Linux starts a new thread on its creator's CPU. A creator that goes straight on working leaves
// it waiting there for the load balancer, up to 4 ms on the 2-core VM (the second thread of a
// 44-58 ms two-thread run began its first tile 2.0 ms late on average; a bare thread started
// 1.8-3.7 ms after its creation while its creator spun, 60-100 us while it slept).

// Runs `body` on a new thread that starts off the caller's current CPU, at once on an idle one,
// and once started may run on every CPU the caller may: kept off only for its start, so that
// more threads than CPUs, or a CPU another program keeps busy, still balance as the system sees
// fit. Where the caller may use a single CPU, a plain thread.
std::thread start_off_callers_cpu(std::function<void()> body);

// The first half of it: `thread` may run on every CPU the caller may but the caller's current one
// (left alone where the caller may use a single CPU, or the system will not move it).
void keep_off_callers_cpu(std::thread& thread);

}  // namespace aesim
