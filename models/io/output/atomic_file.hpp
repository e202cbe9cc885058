#pragma once
#include <ostream>
#include <memory>
#include <string>
#include <vector>

namespace aesim {

// An output a command was asked for: the option that named it (for messages) and its path.
struct OutputPath {
  std::string option, path;
};

// Checks, before any work starts, that every named output can be written: its folder exists or
// can be created and is writable, it is not a folder (nor ends in /), a block device or a socket
// (a character device or FIFO is written through, see OutputFiles), it is not one of the inputs,
// and no two outputs are the same file. Empty paths are skipped. Throws InputError naming the option.
void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs);

// The descriptor a path names when it is a name for one of the process's own open descriptors
// (/dev/stdin, /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N, /proc/<this pid>/fd/N), else -1.
int descriptor_named(const std::string& path);

// A set of output files written to temporary names beside their targets (see temp_files.hpp)
// and renamed into place only by commit(), all or none: a run that fails part-way, or is
// interrupted, leaves no half-written output and no temporaries. Files not committed are
// removed when the set is destroyed. An output that is a link is written to the file it names.
// An output that is a character device or a FIFO (or a name in /dev or under /proc, such as
// /dev/stdout or /dev/fd/3; not a file in a folder below /dev, such as /dev/shm) is written
// through, never replaced: opened at once (a name for a descriptor of this process is that
// descriptor, duplicated, so its offset is shared) and written as the run goes, never seeked (what a
// library writes goes through a temporary copied in at the commit), so it has no all-or-none
// promise; a FIFO with no reader is refused.
class OutputFiles {
 public:
  OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Opens a temporary file for `path` (creating its folder); throws InputError if impossible.
  std::ostream& open(const std::string& path);
  // A temporary name for `path` that someone else writes (e.g. a library or a tool), renamed
  // with the rest. The file exists (empty) when this returns.
  std::string adopt(const std::string& path);
  // The temporary file standing for `target` (opened or adopted here) until the commit.
  std::string temp_path(const std::string& target) const;
  // Flushes every open file, so that a tool can read a temporary before the commit; throws
  // OutputError with the system's reason (e.g. no space left on device) if writing failed.
  void flush();
  // Flushes and renames every file into place; if a rename fails, the targets are restored.
  void commit();

 private:
  class FileBuffer;
  struct Pending {
    std::string target, temp;
    bool direct = false;  // a device or FIFO, written through
    std::unique_ptr<FileBuffer> buffer;
    std::unique_ptr<std::ostream> stream;
    ~Pending();
  };
  std::vector<std::unique_ptr<Pending>> files_;
};

}  // namespace aesim
