// SerialWorker runs a writer's jobs (an .aedat4's compression and writing) on a thread of its own:
// every job once, in the order posted; a job's error back to the poster, with nothing after it run
// and nothing hanging; a worker dropped without drain() runs no more.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "aesim/threads/serial_worker.hpp"

namespace aesim {
namespace {

TEST(SerialWorker, RunsEveryJobOnceInTheOrderPosted) {
  std::vector<int> ran;
  std::atomic<int> waiting{0}, most{0};
  SerialWorker worker(3);
  for (int i = 0; i < 5000; ++i) {
    const int now_waiting = ++waiting;
    int seen = most.load();
    while (now_waiting > seen && !most.compare_exchange_weak(seen, now_waiting)) {
    }
    worker.post([&ran, &waiting, i] {
      --waiting;
      ran.push_back(i);
    });
  }
  worker.drain();
  ASSERT_EQ(ran.size(), 5000u);
  for (int i = 0; i < 5000; ++i) ASSERT_EQ(ran[static_cast<std::size_t>(i)], i);
  // Three waiting, one running, and the one being posted: never more posted and not yet started.
  EXPECT_LE(most.load(), 5);
}

TEST(SerialWorker, AJobsErrorReachesThePosterAndNothingAfterItRuns) {
  std::atomic<int> ran{0};
  SerialWorker worker(2);
  bool thrown = false;
  try {
    for (int i = 0; i < 1000; ++i) {
      worker.post([&ran, i] {
        if (i == 10) throw std::runtime_error("disk full");
        ++ran;
      });
    }
    worker.drain();
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_STREQ(e.what(), "disk full");
  }
  EXPECT_TRUE(thrown);
  EXPECT_EQ(ran.load(), 10);
  EXPECT_THROW(worker.drain(), std::runtime_error);
}

TEST(SerialWorker, DroppedWithoutDrainItFinishesTheJobRunningAndRunsNoMore) {
  std::atomic<int> ran{0};
  std::atomic<bool> started{false};
  {
    SerialWorker worker(8);
    worker.post([&] {
      started = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      ++ran;
    });
    for (int i = 0; i < 5; ++i) worker.post([&ran] { ++ran; });
    while (!started) std::this_thread::yield();
  }
  EXPECT_EQ(ran.load(), 1);
}

}  // namespace
}  // namespace aesim
