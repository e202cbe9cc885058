#include "aesim/output/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/descriptor_io.hpp"
#include "aesim/output/space_ahead.hpp"
#include "aesim/output/temp_files.hpp"

namespace aesim {
namespace fs = std::filesystem;
namespace {

fs::path folder_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// An output that is a character device or a FIFO, or a name the system gives an open file (/dev/stdout,
// /dev/fd/N, /proc/self/fd/N: whatever it leads to is the caller's, a shell's redirection say), is
// written through: opened and written as it is, never replaced by a file renamed over it. A file in
// a folder below /dev (a tmpfs such as /dev/shm) is an ordinary file.
bool write_through(const std::string& path) {
  std::error_code ec;
  const fs::file_type type = fs::status(path, ec).type();
  if (type == fs::file_type::character || type == fs::file_type::fifo) return true;
  const fs::path absolute = fs::absolute(path, ec).lexically_normal();
  fs::path folder = fs::weakly_canonical(absolute.parent_path(), ec);
  if (ec) folder = absolute.parent_path();
  const std::string f = folder.string();
  return f == "/dev" || f == "/proc" || f.rfind("/proc/", 0) == 0;
}

// The same file by its device and inode (std::filesystem::equivalent refuses FIFOs and devices).
bool same_inode(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

// The file a link names (an output through a link replaces the file, not the link).
std::string resolved(const std::string& path) {
  std::error_code ec;
  if (!fs::is_symlink(path, ec)) return path;
  const fs::path target = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? path : target.string();
}

// The same file, whether or not it exists yet (links and relative spellings resolved).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return same_inode(a, b);
  return fs::weakly_canonical(fs::absolute(a, ec), ec) == fs::weakly_canonical(fs::absolute(b, ec), ec);
}

// Two names of one stream written through: the same descriptor of this process (/dev/stdout and
// /dev/fd/1, wherever it leads), or the same FIFO or device other than /dev/null, which keeps nothing.
bool same_stream(const std::string& a, const std::string& b) {
  const int fa = descriptor_named(a);
  if (fa >= 0 && fa == descriptor_named(b)) return true;
  return same_file(a, b) && !same_inode(a, "/dev/null");
}

}  // namespace

int descriptor_named(const std::string& path) {
  std::error_code ec;
  const std::string p = fs::absolute(path, ec).lexically_normal().string();
  if (p == "/dev/stdin") return 0;
  if (p == "/dev/stdout") return 1;
  if (p == "/dev/stderr") return 2;
  for (const std::string& folder : {std::string("/dev/fd/"), std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"),
                                    fmt::format("/proc/{}/fd/", ::getpid())}) {
    if (p.size() <= folder.size() || p.compare(0, folder.size(), folder) != 0) continue;
    const std::string number = p.substr(folder.size());
    if (number.size() > 9 || number.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoi(number);
  }
  return -1;
}

void check_output_paths(const std::vector<OutputPath>& outputs, const std::vector<std::string>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputPath& o = outputs[i];
    if (o.path.empty()) continue;
    std::error_code ec;
    if (fs::is_directory(o.path, ec)) throw InputError(fmt::format("{} '{}': is a folder, not a file", o.option, o.path));
    if (o.path.back() == '/') throw InputError(fmt::format("{} '{}': names a folder (ends in /), not a file", o.option, o.path));
    const fs::file_type type = fs::status(o.path, ec).type();
    if (type == fs::file_type::block || type == fs::file_type::socket) {
      throw InputError(fmt::format("{} '{}': is a {}; aesim writes files, character devices (such as /dev/null) and FIFOs",
                                   o.option, o.path, type == fs::file_type::block ? "block device" : "socket"));
    }
    if (write_through(o.path)) {
      // Written as it is: it must exist and be writable; nothing is made beside it.
      if (::access(o.path.c_str(), W_OK) != 0) {
        throw InputError(fmt::format("{} '{}': cannot write: {}", o.option, o.path, std::strerror(errno)));
      }
      // Two outputs into one stream or FIFO would interleave into neither format; a device that
      // keeps nothing (/dev/null) may take any number.
      for (std::size_t j = 0; j < i; ++j) {
        if (!outputs[j].path.empty() && same_stream(o.path, outputs[j].path)) {
          throw InputError(fmt::format("{} and {} both write into '{}'", outputs[j].option, o.option, o.path));
        }
      }
      continue;
    }
    // The nearest folder that exists must be a writable folder (the rest is created later).
    fs::path folder = folder_of(o.path);
    while (!fs::exists(folder, ec) && folder.has_parent_path() && folder.parent_path() != folder) {
      folder = folder.parent_path();
    }
    if (!fs::exists(folder, ec)) folder = ".";
    if (!fs::is_directory(folder, ec)) {
      throw InputError(fmt::format("{} '{}': '{}' is not a folder", o.option, o.path, folder.string()));
    }
    if (::access(folder.c_str(), W_OK | X_OK) != 0) {
      throw InputError(fmt::format("{} '{}': cannot write in '{}': {}", o.option, o.path, folder.string(),
                                   std::strerror(errno)));
    }
    for (const std::string& in : inputs) {
      if (!in.empty() && same_file(o.path, in)) {
        throw InputError(fmt::format("{} '{}' would overwrite the input '{}'", o.option, o.path, in));
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].path.empty() && same_file(o.path, outputs[j].path)) {
        throw InputError(fmt::format("{} and {} both name '{}'", outputs[j].option, o.option, o.path));
      }
    }
  }
}

// A file writer over a descriptor, with its own buffer of kFileBufferBytes, that keeps the reason of
// its first failed write (std::ofstream loses errno): a full disk is reported as "No space left on
// device". A block at least as large as the buffer goes to the system as it is, not copied. A
// temporary reserves its disk space ahead of its writes (SpaceAhead), given back at each flush.
class OutputFiles::FileBuffer : public std::streambuf {
 public:
  // `seekable` false for an output written through: its offset may be shared with whoever opened
  // the descriptor, so a position read from it is not the output's own.
  // No descriptor (a file a library writes by its name): no buffer either.
  FileBuffer(int fd, bool seekable) : fd_(fd), seekable_(seekable), buffer_(fd >= 0 ? kFileBufferBytes : 0) {
    reset_put_area();
  }
  ~FileBuffer() override { close(); }

  bool close() {
    if (fd_ < 0) return error_ == 0;
    sync();
    if (::close(fd_) != 0 && error_ == 0) error_ = errno;
    fd_ = -1;
    return error_ == 0;
  }
  bool is_open() const { return fd_ >= 0; }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (ch != traits_type::eof()) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override {
    const bool ok = drain();
    if (seekable_) space_.release(fd_);
    return ok ? 0 : -1;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n < static_cast<std::streamsize>(buffer_.size())) return std::streambuf::xsputn(s, n);
    if (!drain() || !write_all(s, static_cast<std::size_t>(n))) return 0;
    return n;
  }
  // Seeking, for writers that patch what they wrote first (AEDAT 4.0's header); a device or FIFO
  // cannot seek, and says so by -1.
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    if (!seekable_ || !drain()) return pos_type(off_type(-1));
    const int whence = dir == std::ios_base::beg ? SEEK_SET : dir == std::ios_base::cur ? SEEK_CUR : SEEK_END;
    const off_t at = ::lseek(fd_, static_cast<off_t>(off), whence);
    if (at < 0) return pos_type(off_type(-1));
    offset_ = static_cast<std::uint64_t>(at);
    return pos_type(static_cast<off_type>(at));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }

 private:
  bool write_all(const char* p, std::size_t n) {
    if (error_ != 0 || n == 0) return error_ == 0;
    if (seekable_) space_.before_writing_to(fd_, offset_ + n);
    error_ = write_fully(fd_, p, n);
    offset_ += n;
    return error_ == 0;
  }
  bool drain() {
    const bool ok = write_all(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    reset_put_area();
    return ok;
  }
  void reset_put_area() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }

  // Large writes cost the system less: a megabyte a call took a tenth off writing .npy to the page
  // cache against 64 KiB (event_rate_bench).
  static constexpr std::size_t kFileBufferBytes = std::size_t(1) << 20;
  int fd_;
  bool seekable_;
  int error_ = 0;
  std::vector<char> buffer_;
  std::uint64_t offset_ = 0;  // where the descriptor writes next (a temporary: opened empty, its own)
  SpaceAhead space_;
};

OutputFiles::OutputFiles() = default;
OutputFiles::Pending::~Pending() = default;

OutputFiles::~OutputFiles() {
  for (auto& f : files_) {
    if (f->temp.empty()) continue;
    if (f->buffer) f->buffer->close();
    std::error_code ignored;
    fs::remove(f->temp, ignored);
    unregister_temp(f->temp);
  }
}

// A device or FIFO, opened for writing. A FIFO with no reader is refused rather than waited on. A
// name for one of the process's own descriptors is that descriptor, duplicated: opened anew, a
// regular file behind it (a shell's `> file`) would get an offset of its own, and the run's data and
// anything else written to the descriptor would overwrite each other from the file's start.
int open_through(const std::string& path) {
  const int named = descriptor_named(path);
  if (named >= 0) {
    const int fd = ::fcntl(named, F_DUPFD_CLOEXEC, 0);
    if (fd < 0) throw InputError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
    return fd;
  }
  int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 && errno == ENXIO) throw InputError(fmt::format("output '{}': a FIFO with no reader", path));
  if (fd < 0) throw InputError(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

std::ostream& OutputFiles::open(const std::string& path) {
  auto f = std::make_unique<Pending>();
  f->target = path;
  if (write_through(path)) {
    f->direct = true;
    f->buffer = std::make_unique<FileBuffer>(open_through(path), false);
    f->stream = std::make_unique<std::ostream>(f->buffer.get());
    files_.push_back(std::move(f));
    return *files_.back()->stream;
  }
  f->target = resolved(path);
  f->temp = temp_name_for(f->target);
  const fs::path parent = fs::path(f->target).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw InputError(fmt::format("cannot create folder '{}': {}", parent.string(), ec.message()));
  remove_stale_temps(folder_of(f->target).string());
  register_temp(f->temp);
  const int fd = ::open(f->temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    unregister_temp(f->temp);
    throw InputError(fmt::format("cannot write '{}': {}", path, std::strerror(err)));
  }
  f->buffer = std::make_unique<FileBuffer>(fd, true);
  f->stream = std::make_unique<std::ostream>(f->buffer.get());
  files_.push_back(std::move(f));
  return *files_.back()->stream;
}

std::string OutputFiles::adopt(const std::string& path) {
  if (write_through(path)) {
    // A library writes a file (it may seek): a temporary in the system's temporary folder, copied
    // into the device or FIFO at the commit.
    auto f = std::make_unique<Pending>();
    f->target = path;
    f->direct = true;
    std::error_code ec;
    const fs::path tmp = fs::temp_directory_path(ec);
    f->temp = temp_name_for(((ec ? fs::path("/tmp") : tmp) / fs::path(path).filename()).string());
    register_temp(f->temp);
    const int fd = ::open(f->temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) {
      unregister_temp(f->temp);
      throw InputError(fmt::format("cannot write a temporary for '{}': {}", path, std::strerror(errno)));
    }
    ::close(fd);
    f->buffer = std::make_unique<FileBuffer>(-1, false);
    files_.push_back(std::move(f));
    return files_.back()->temp;
  }
  open(path);
  files_.back()->buffer->close();
  return files_.back()->temp;
}

std::string OutputFiles::temp_path(const std::string& target) const {
  for (const auto& f : files_) {
    if (f->target == target || f->target == resolved(target)) return f->temp;
  }
  throw std::logic_error("no output file " + target);
}

void OutputFiles::flush() {
  for (auto& f : files_) {
    if (!f->buffer->is_open()) continue;  // adopted: written and closed by its writer
    f->stream->flush();
    if (f->buffer->error() != 0 || !*f->stream) {
      throw OutputError(fmt::format("writing '{}' failed: {}", f->target,
                                    f->buffer->error() != 0 ? std::strerror(f->buffer->error()) : "a writer failed"));
    }
  }
}

void OutputFiles::commit() {
  flush();
  for (auto& f : files_) {
    if (!f->buffer->close()) {
      throw OutputError(fmt::format("writing '{}' failed: {}", f->target, std::strerror(f->buffer->error())));
    }
  }
  // Devices and FIFOs: what was written through is there; what a library wrote is copied in.
  for (auto& f : files_) {
    if (!f->direct || f->temp.empty()) continue;
    const int in = ::open(f->temp.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) throw OutputError(fmt::format("reading the temporary for '{}': {}", f->target, std::strerror(errno)));
    FileBuffer out(open_through(f->target), false);
    std::ostream stream(&out);
    char chunk[1 << 16];
    ssize_t n = 0;
    while ((n = read_fully(in, chunk, sizeof chunk)) > 0) stream.write(chunk, n);
    const int read_error = n < 0 ? errno : 0;
    ::close(in);
    if (read_error != 0) {
      throw OutputError(fmt::format("reading the temporary for '{}': {}", f->target, std::strerror(read_error)));
    }
    if (!out.close()) throw OutputError(fmt::format("writing '{}' failed: {}", f->target, std::strerror(out.error())));
  }
  // Keep what the targets held, so that a failed rename can put every one of them back.
  std::vector<std::string> backups(files_.size());
  for (std::size_t i = 0; i < files_.size(); ++i) {
    std::error_code ec;
    if (files_[i]->direct || !fs::is_regular_file(files_[i]->target, ec)) continue;
    backups[i] = temp_name_for(files_[i]->target, ".old");
    fs::remove(backups[i], ec);
    if (::link(files_[i]->target.c_str(), backups[i].c_str()) != 0) backups[i].clear();
  }
  auto drop_backups = [&] {
    for (const std::string& b : backups) {
      std::error_code ignored;
      if (!b.empty()) fs::remove(b, ignored);
    }
  };
  for (std::size_t i = 0; i < files_.size(); ++i) {
    std::error_code ec;
    if (files_[i]->direct) continue;
    fs::rename(files_[i]->temp, files_[i]->target, ec);
    if (!ec) continue;
    for (std::size_t j = 0; j < i; ++j) {
      if (files_[j]->direct) continue;
      std::error_code ignored;
      if (!backups[j].empty()) fs::rename(backups[j], files_[j]->target, ignored);
      else fs::remove(files_[j]->target, ignored);
    }
    drop_backups();
    throw OutputError(fmt::format("cannot rename into '{}': {}", files_[i]->target, ec.message()));
  }
  drop_backups();
  for (auto& f : files_) {
    std::error_code ignored;
    if (f->direct && !f->temp.empty()) fs::remove(f->temp, ignored);
    unregister_temp(f->temp);
    f->temp.clear();
  }
}

}  // namespace aesim
