#include "aesim/output/temp_files.hpp"

#include "aesim/process/child_process.hpp"

#include "aesim/process/interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

namespace aesim {
namespace fs = std::filesystem;
namespace {

constexpr const char* kMarker = ".aesim-tmp.";

std::string host_name() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) return "localhost";
  std::string h = name.data();
  for (char& c : h) c = (c == '/' || c == '.') ? '_' : c;  // one path component, no dots
  return h.empty() ? "localhost" : h;
}

// The handler may only touch plain memory: fixed slots of C strings, claimed atomically.
constexpr std::size_t kSlots = 256;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<bool> claimed{false}, ready{false};  // ready only once path is complete
  char path[kPathMax];
};
Slot g_slots[kSlots];
volatile sig_atomic_t g_cooperative = 0;

void on_signal(int sig) {
  const int saved = errno;
  request_interrupt(sig);
  if (g_cooperative) {
    errno = saved;
    return;
  }
  for (Slot& s : g_slots) {
    if (s.ready.load()) ::unlink(s.path);
  }
  kill_children(SIGTERM);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

std::string temp_name_for(const std::string& target, const std::string& suffix) {
  const fs::path p(target);
  const std::string name = p.filename().string();
  const std::string temp = fmt::format(".{}{}{}{}.{}", name, suffix, kMarker, host_name(), ::getpid());
  return (p.parent_path() / temp).string();
}

std::string target_of(const std::string& path) {
  const fs::path p(path);
  const std::string name = p.filename().string();
  const std::size_t at = name.find(kMarker);
  if (name.size() < 2 || name[0] != '.' || at == std::string::npos) return path;
  return (p.parent_path() / name.substr(1, at - 1)).string();
}

std::string write_failure(const std::string& path) {
  const int err = errno;
  return fmt::format("writing '{}' failed: {}", target_of(path), err ? std::strerror(err) : "the writer gave no reason");
}

void remove_stale_temps(const std::string& folder) {
  const std::string mine = std::string(kMarker) + host_name() + ".";
  std::error_code ec;
  fs::directory_iterator it(folder.empty() ? "." : folder, ec);
  if (ec) return;
  for (const fs::directory_entry& e : it) {
    const std::string name = e.path().filename().string();
    const std::size_t at = name.rfind(mine);
    if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
    const std::string pid_text = name.substr(at + mine.size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to judge
    std::error_code ignored;
    fs::remove_all(e.path(), ignored);
  }
}

void register_temp(const std::string& path) {
  if (path.size() >= kPathMax) return;  // too long to hold; still removed by the destructor path
  for (Slot& s : g_slots) {
    bool expected = false;
    if (!s.claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(s.path, path.c_str(), path.size() + 1);
    s.ready.store(true);
    return;
  }
}

void unregister_temp(const std::string& path) {
  for (Slot& s : g_slots) {
    if (s.ready.load() && path == s.path) {
      s.ready.store(false);
      s.claimed.store(false);
      return;
    }
  }
}

void install_signal_cleanup() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a cooperative command's waitpid returns EINTR
  // Every signal whose default ends the process (but SIGKILL and SIGSTOP, which cannot be caught).
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGPIPE, SIGALRM, SIGVTALRM, SIGXCPU, SIGXFSZ}) {
    ::sigaction(sig, &action, nullptr);
  }
}

Cooperative::Cooperative() { g_cooperative = 1; }
Cooperative::~Cooperative() { g_cooperative = 0; }

}  // namespace aesim
