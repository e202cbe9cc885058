#include "aesim/threads/thread_placement.hpp"

#include <atomic>
#include <memory>

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif

namespace aesim {

void keep_off_callers_cpu(std::thread& thread) {
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const int cpu = sched_getcpu();
  if (cpu < 0 || sched_getaffinity(0, sizeof allowed, &allowed) != 0) return;
  if (!CPU_ISSET(cpu, &allowed) || CPU_COUNT(&allowed) < 2) return;
  CPU_CLR(cpu, &allowed);
  pthread_setaffinity_np(thread.native_handle(), sizeof allowed, &allowed);
#else
  (void)thread;
#endif
}

std::thread start_off_callers_cpu(std::function<void()> body) {
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0 || CPU_COUNT(&allowed) < 2) return std::thread(std::move(body));
  // The thread gives itself the caller's CPUs back only after the caller has kept it off its own:
  // in the other order the restriction would stay for good.
  auto placed = std::make_shared<std::atomic<bool>>(false);
  std::thread thread([placed, allowed, body = std::move(body)] {
    while (!placed->load(std::memory_order_acquire)) std::this_thread::yield();
    sched_setaffinity(0, sizeof allowed, &allowed);
    body();
  });
  keep_off_callers_cpu(thread);
  placed->store(true, std::memory_order_release);
  return thread;
#else
  return std::thread(std::move(body));
#endif
}

}  // namespace aesim
