#pragma once
#include <thread>

namespace aesim {

// Linux starts a new thread on its creator's CPU. A creator that goes straight on working leaves
// it waiting there for the load balancer, up to 4 ms on the 2-core VM (the second thread of a
// 44-58 ms two-thread run began its first tile 2.0 ms late on average; a bare thread started
// 1.8-3.7 ms after its creation while its creator spun, 60-100 us while it slept). Called by the
// creator right after starting `thread`, this keeps the thread off the creator's current CPU, so
// that it starts at once on an idle one. Only where the process may use more than one CPU; the
// creator's own placement is left alone, and a thread the system will not move runs where it was
// put.
void keep_off_callers_cpu(std::thread& thread);

}  // namespace aesim
