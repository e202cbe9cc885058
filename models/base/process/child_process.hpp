#pragma once
#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace aesim {

// Where a child's standard output and error go: inherited when empty, else this file (truncated);
// and the folder it runs in (the caller's when empty), so tools that take file names in scripts
// (yosys, ABC) need no paths at all.
struct ChildOutput {
  ChildOutput() = default;
  ChildOutput(std::string out, std::string err, std::string dir = {})
      : stdout_path(std::move(out)), stderr_path(std::move(err)), working_dir(std::move(dir)) {}
  std::string stdout_path, stderr_path;
  std::string working_dir;
};

// Starts a program with an argument vector: no shell ever sees any of the strings, so paths and
// values from users reach the tool as data. `program` is looked up on PATH unless it has a '/'.
// Throws ToolMissing if it cannot be found, std::runtime_error if it cannot start.
pid_t spawn_child(const std::string& program, const std::vector<std::string>& args, const ChildOutput& output = {});

// Waits for a child; returns its exit status, or 128 + the signal that ended it.
int wait_child(pid_t pid);

// Waits at most `seconds` for a child; past that, kills it (SIGKILL), reaps it and returns
// nullopt, so that a tool that runs away cannot hang the command that started it.
std::optional<int> wait_child_for(pid_t pid, double seconds);
// The same, and ends the child early (as past the deadline) as soon as `keep_waiting`, asked every
// `poll_seconds`, says there is no point: a tool whose own progress shows it will not finish.
std::optional<int> wait_child_while(pid_t pid, double seconds, const std::function<bool()>& keep_waiting,
                                    double poll_seconds);

// spawn_child then wait_child.
int run_child(const std::string& program, const std::vector<std::string>& args, const ChildOutput& output = {});

// Runs `work` in a forked copy of this process, for a call into a library that can crash on
// hostile input (HDF5 1.10 dereferences null on some corrupt files): `work` writes its answer to
// the pipe it is given and the copy exits, so a crash costs the copy, never the caller. The
// caller reads `fd` (closing it) and then wait_child(pid): 0 when `work` returned, 128 + the
// signal that ended it otherwise.
struct IsolatedWork {
  pid_t pid = -1;
  int fd = -1;
};
IsolatedWork fork_isolated(const std::function<void(int fd)>& work);

// Lets this process map at most `bytes` more memory than it has mapped now (RLIMIT_DATA, which
// counts the heap and every private writable mapping): a forked copy about to read a hostile file,
// whose library may allocate, and fill, whatever size a corrupt header claims, then fails that
// allocation instead of taking the machine's memory. Does nothing where the kernel cannot say.
void limit_memory_growth(std::uint64_t bytes);

// Sends `sig` to every child spawn_child started that no wait has reaped yet: a signal handler
// calls it (it is async-signal-safe), so that aesim stopped by a signal leaves no compiler or
// solver running on.
void kill_children(int sig);

// Whether `program` names an executable on PATH (or, with a '/', an executable file).
bool program_available(const std::string& program);

class ToolMissing : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace aesim
