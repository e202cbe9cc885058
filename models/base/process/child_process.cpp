#include "aesim/process/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cerrno>
#include <chrono>
#include <thread>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

// GCC says so with a macro (ASan only), clang through __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define AESIM_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define AESIM_SANITIZED 1
#endif
#endif
#ifdef AESIM_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

extern char** environ;

namespace aesim {
namespace {

// The children running now, for a signal handler to stop with the process (kill() is
// async-signal-safe; the table is fixed and lock-free).
constexpr int kChildSlots = 64;
std::atomic<pid_t> g_children[kChildSlots];

void remember_child(pid_t pid) {
  for (auto& slot : g_children) {
    pid_t empty = 0;
    if (slot.compare_exchange_strong(empty, pid)) return;
  }
}

void forget_child(pid_t pid) {
  for (auto& slot : g_children) {
    pid_t mine = pid;
    if (slot.compare_exchange_strong(mine, 0)) return;
  }
}

}  // namespace

void kill_children(int sig) {
  for (auto& slot : g_children) {
    const pid_t pid = slot.load();
    if (pid > 0) ::kill(-pid, sig);
  }
}

bool program_available(const std::string& program) {
  if (program.empty()) return false;
  if (program.find('/') != std::string::npos) return ::access(program.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string candidate = dir + "/" + program;
    std::error_code ec;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate, ec)) return true;
    start = end + 1;
  }
  return false;
}

pid_t spawn_child(const std::string& program, const std::vector<std::string>& args, const ChildOutput& output) {
  if (!program_available(program)) throw ToolMissing(fmt::format("'{}' is not installed (not found on PATH)", program));
  std::vector<std::string> owned;
  owned.reserve(args.size() + 1);
  owned.push_back(program);
  owned.insert(owned.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : owned) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!output.stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.stdout_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (!output.stderr_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, output.stderr_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (!output.working_dir.empty()) posix_spawn_file_actions_addchdir_np(&actions, output.working_dir.c_str());
  // Each child leads a process group of its own, so that kill_children stops what it started too
  // (a compiler driver's cc1plus, a shell's commands).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, program.c_str(), &actions, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error(fmt::format("cannot start '{}': {}", program, std::strerror(rc)));
  remember_child(pid);
  return pid;
}

int wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(fmt::format("waiting for a child process: {}", std::strerror(errno)));
  }
  forget_child(pid);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;
}

std::optional<int> wait_child_for(pid_t pid, double seconds) {
  return wait_child_while(pid, seconds, [] { return true; }, seconds);
}

std::optional<int> wait_child_while(pid_t pid, double seconds, const std::function<bool()>& keep_waiting,
                                    double poll_seconds) {
  // Polling keeps SIGCHLD alone (other threads run children too); a child of a tool's run lasts
  // seconds, so a 2 ms poll costs little.
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::duration<double>(seconds);
  auto next_ask = start + std::chrono::duration<double>(poll_seconds);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      forget_child(pid);
      if (WIFEXITED(status)) return WEXITSTATUS(status);
      return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;
    }
    if (done < 0 && errno != EINTR) {
      throw std::runtime_error(fmt::format("waiting for a child process: {}", std::strerror(errno)));
    }
    const auto now = std::chrono::steady_clock::now();
    bool give_up = now > deadline;
    if (!give_up && now > next_ask) {
      next_ask = now + std::chrono::duration<double>(poll_seconds);
      give_up = !keep_waiting();
    }
    if (give_up) {
      ::kill(-pid, SIGKILL);
      wait_child(pid);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

IsolatedWork fork_isolated(const std::function<void(int fd)>& work) {
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("cannot make a pipe: {}", std::strerror(errno)));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(ends[0]);
    ::close(ends[1]);
    throw std::runtime_error(fmt::format("cannot fork: {}", std::strerror(err)));
  }
  if (pid == 0) {
    ::close(ends[0]);
    ::setpgid(0, 0);
    // A crash here ends this copy with its signal: no handler of the parent's (aesim's cleanup,
    // a sanitizer's report-and-die hooks) runs in it.
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGPIPE}) std::signal(sig, SIG_DFL);
#ifdef AESIM_SANITIZED
    __sanitizer_set_death_callback(nullptr);
#endif
    int status = 0;
    try {
      work(ends[1]);
    } catch (...) {
      status = 1;
    }
    ::close(ends[1]);
    ::_exit(status);
  }
  ::close(ends[1]);
  remember_child(pid);
  return {pid, ends[0]};
}

void limit_memory_growth(std::uint64_t bytes) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmData:", 0) != 0) continue;
    const std::uint64_t mapped = std::strtoull(line.c_str() + 7, nullptr, 10) * 1024;  // kB
    if (mapped == 0) return;
    const rlimit limit{static_cast<rlim_t>(mapped + bytes), static_cast<rlim_t>(mapped + bytes)};
    ::setrlimit(RLIMIT_DATA, &limit);
    return;
  }
}

int run_child(const std::string& program, const std::vector<std::string>& args, const ChildOutput& output) {
  return wait_child(spawn_child(program, args, output));
}

}  // namespace aesim
