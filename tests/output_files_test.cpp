// How outputs reach their descriptors. Disk space reserved ahead of an output's writes
// (SpaceAhead), by OutputFiles' temporaries and the .npy writer: the reservation lies past the
// file's end while it grows, and none is left once the file is written; the bytes are the bytes
// written either way. The writes every output goes through (descriptor_io): all the bytes, in
// order, through signals and short writes, and the system's reason when they cannot go.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/event_files/npy_events.hpp"
#include "aesim/files/descriptor_io.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/output/space_ahead.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

constexpr std::uint64_t kMiB = std::uint64_t(1) << 20;

// Bytes the filesystem holds for `path` (st_blocks counts 512-byte units).
std::uint64_t allocated(const std::string& path) {
  struct stat s {};
  EXPECT_EQ(::stat(path.c_str(), &s), 0) << path;
  return static_cast<std::uint64_t>(s.st_blocks) * 512;
}

class OutputFilesTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    // Where the test folder's filesystem cannot reserve (fallocate), there is nothing to see.
    const std::string probe = (dir_ / "probe").string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    const bool can = ::fallocate(fd, FALLOC_FL_KEEP_SIZE, 0, static_cast<off_t>(kMiB)) == 0;
    ::close(fd);
    fs::remove(probe);
    if (!can) GTEST_SKIP() << "the temporary folder's filesystem does not reserve space (fallocate)";
  }
  // `n` bytes of a pattern that shows any byte out of place.
  static std::string pattern(std::size_t n, unsigned seed) {
    std::string s(n, '\0');
    for (std::size_t i = 0; i < n; ++i) s[i] = static_cast<char>((i * 131 + seed) >> 3);
    return s;
  }
};

TEST_F(OutputFilesTest, SpaceIsReservedPastTheEndOnlyOnceAFilePassesAMegabyteAndGivenBack) {
  const std::string path = (dir_ / "f").string();
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  SpaceAhead space;
  const std::string block = pattern(512 * 1024, 1);
  std::string written;
  // Two half-megabyte writes: up to the first megabyte nothing is reserved.
  for (int i = 0; i < 2; ++i) {
    space.before_writing_to(fd, written.size() + block.size());
    ASSERT_EQ(::write(fd, block.data(), block.size()), static_cast<ssize_t>(block.size()));
    written += block;
  }
  EXPECT_LT(allocated(path), written.size() + 64 * 1024);
  // The third passes it: 16 MiB past the write's end are reserved, and the size is what was written.
  space.before_writing_to(fd, written.size() + block.size());
  ASSERT_EQ(::write(fd, block.data(), block.size()), static_cast<ssize_t>(block.size()));
  written += block;
  EXPECT_EQ(fs::file_size(path), written.size());
  EXPECT_GE(allocated(path), written.size() + 16 * kMiB);
  // Writes within the reservation reserve no more.
  space.before_writing_to(fd, written.size() + block.size());
  EXPECT_LT(allocated(path), written.size() + 17 * kMiB + 64 * 1024);
  space.release(fd);
  ::close(fd);
  EXPECT_EQ(fs::file_size(path), written.size());
  EXPECT_LT(allocated(path), written.size() + 64 * 1024);
  EXPECT_EQ(slurp(path), written);
}

// A descriptor that cannot reserve (a pipe): nothing fails, and nothing more is tried.
TEST_F(OutputFilesTest, ADescriptorThatCannotReserveIsWrittenAsItIs) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  SpaceAhead space;
  space.before_writing_to(pipe_fds[1], 4 * kMiB);
  space.before_writing_to(pipe_fds[1], 40 * kMiB);
  space.release(pipe_fds[1]);
  ASSERT_EQ(::write(pipe_fds[1], "ok", 2), 2);
  char got[2];
  ASSERT_EQ(::read(pipe_fds[0], got, 2), 2);
  EXPECT_EQ(std::string(got, 2), "ok");
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
}

// Through OutputFiles, as every event writer but .npy's and HDF5's writes: a flush gives the
// reservation back (a writer's finish flushes), so other outputs of the run find the space free;
// the committed file holds its bytes and no more.
TEST_F(OutputFilesTest, AnOutputFileGivesItsReservationBackAtAFlushAndCommitsItsBytes) {
  const std::string target = (dir_ / "out.bin").string();
  const std::string data = pattern(5 * kMiB + 123, 7);
  OutputFiles files;
  std::ostream& out = files.open(target);
  for (std::size_t at = 0; at < data.size(); at += 300000) out.write(data.data() + at, static_cast<std::streamsize>(std::min<std::size_t>(300000, data.size() - at)));
  const std::string temp = files.temp_path(target);
  EXPECT_GE(allocated(temp), 16 * kMiB) << "reserved while the file grows";
  out.flush();
  EXPECT_LT(allocated(temp), data.size() + 64 * 1024);
  files.commit();
  EXPECT_EQ(slurp(target), data);
  EXPECT_LT(allocated(target), data.size() + 64 * 1024);
}

// The .npy writer reserves on its own descriptor; the file it finishes is its records and no more.
TEST_F(OutputFilesTest, TheNpyWriterLeavesNoReservationBehind) {
  const std::string path = (dir_ / "e.npy").string();
  std::vector<AddressEvent> events(200000);
  for (std::size_t i = 0; i < events.size(); ++i) {
    events[i].t = static_cast<double>(i) * 1e-6;
    events[i].x = static_cast<std::uint32_t>(i % 176);
    events[i].y = static_cast<std::uint32_t>(i % 144);
  }
  NpyWriter writer(path, 1e-6);
  writer.events(events.data(), events.size());
  EXPECT_GE(allocated(path), 16 * kMiB) << "reserved while the file grows";
  writer.finish();
  const std::string data = slurp(path);
  ASSERT_EQ(data.size(), 256 + 13 * events.size());
  EXPECT_LT(allocated(path), data.size() + 64 * 1024);
  // The last record: x, y, t (us) and p as written.
  const std::size_t last = events.size() - 1;
  const std::string r = data.substr(256 + 13 * last, 13);
  std::uint16_t x, y;
  std::int64_t t;
  std::memcpy(&x, r.data(), 2);
  std::memcpy(&y, r.data() + 2, 2);
  std::memcpy(&t, r.data() + 4, 8);
  EXPECT_EQ(x, last % 176);
  EXPECT_EQ(y, last % 144);
  EXPECT_EQ(t, static_cast<std::int64_t>(last));
  EXPECT_EQ(r[12], 1);
}

std::atomic<int> alarms{0};
void count_alarm(int) { alarms.fetch_add(1); }

// A run's SIGINT handler is installed without SA_RESTART, so a write blocked on a slow reader
// returns EINTR (nothing written yet) or a short count (some written). A pipe whose reader starts
// late holds a writer blocked while a 2 ms timer interrupts it, dozens of times, both ways.
TEST(DescriptorIoTest, AWriteGoesOnThroughSignalsAndShortWritesWithEveryByteInOrder) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::vector<char> sent(std::size_t(4) << 20);
  for (std::size_t i = 0; i < sent.size(); ++i) sent[i] = static_cast<char>((i * 2654435761u) >> 13);
  // The reader blocks the timer's signal, so that every one lands on the writer.
  sigset_t alarm_only, before;
  sigemptyset(&alarm_only);
  sigaddset(&alarm_only, SIGALRM);
  ASSERT_EQ(::pthread_sigmask(SIG_BLOCK, &alarm_only, &before), 0);
  std::vector<char> got;
  std::thread reader([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    // Then slowly, a pause every 256 KiB, so that the writer blocks again and again.
    char chunk[4096];
    std::size_t chunks = 0;
    for (ssize_t n; (n = read_fully(fds[0], chunk, sizeof chunk)) > 0;) {
      got.insert(got.end(), chunk, chunk + n);
      if (++chunks % 64 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }
  });
  ASSERT_EQ(::pthread_sigmask(SIG_SETMASK, &before, nullptr), 0);
  struct sigaction action {}, old_action {};
  action.sa_handler = count_alarm;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  ASSERT_EQ(::sigaction(SIGALRM, &action, &old_action), 0);
  const itimerval every_2ms{{0, 2000}, {0, 2000}}, off{};
  alarms = 0;
  ASSERT_EQ(::setitimer(ITIMER_REAL, &every_2ms, nullptr), 0);
  const int error = write_fully(fds[1], sent.data(), sent.size());
  ::setitimer(ITIMER_REAL, &off, nullptr);
  ::sigaction(SIGALRM, &old_action, nullptr);
  ::close(fds[1]);
  reader.join();
  ::close(fds[0]);
  EXPECT_EQ(error, 0) << std::strerror(error);
  EXPECT_GT(alarms.load(), 5);
  ASSERT_EQ(got.size(), sent.size());
  EXPECT_TRUE(got == sent);
}

TEST_F(OutputFilesTest, AWriteAtAnOffsetLeavesThePositionAndAReadStopsAtTheEnd) {
  const std::string path = (dir_ / "positions").string();
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  EXPECT_EQ(write_fully(fd, "abc", 3), 0);
  EXPECT_EQ(write_fully_at(fd, "XY", 2, 10), 0);
  EXPECT_EQ(write_fully(fd, "d", 1), 0);
  ASSERT_EQ(::lseek(fd, 0, SEEK_SET), 0);
  char back[100];
  EXPECT_EQ(read_fully(fd, back, sizeof back), 12);
  EXPECT_EQ(std::string(back, 12), std::string("abcd\0\0\0\0\0\0XY", 12));
  EXPECT_EQ(read_fully(fd, back, sizeof back), 0);
  ::close(fd);
}

TEST(DescriptorIoTest, AWriteThatCannotGoReturnsTheSystemsReason) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);
  struct sigaction ignore {}, old_action {};
  ignore.sa_handler = SIG_IGN;
  ASSERT_EQ(::sigaction(SIGPIPE, &ignore, &old_action), 0);
  EXPECT_EQ(write_fully(fds[1], "x", 1), EPIPE);
  ::sigaction(SIGPIPE, &old_action, nullptr);
  ::close(fds[1]);
  EXPECT_EQ(write_fully(fds[1], "x", 1), EBADF);
  char c;
  EXPECT_EQ(read_fully(fds[1], &c, 1), -1);
  EXPECT_EQ(errno, EBADF);
}

}  // namespace
}  // namespace aesim
