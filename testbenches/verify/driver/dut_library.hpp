#pragma once
#include <cstdint>
#include <memory>
#include <string>

namespace aesim {

// A receiver model built by build_dut, loaded into this process (dlopen) through its C interface.
class DutLibrary {
 public:
  explicit DutLibrary(const std::string& path);  // throws InputError if it cannot be loaded
  ~DutLibrary();
  DutLibrary(const DutLibrary&) = delete;
  DutLibrary& operator=(const DutLibrary&) = delete;

  using CreateFn = void* (*)(int);
  using DestroyFn = void (*)(void*);
  using EvalFn = void (*)(void*);
  using PortFn = void* (*)(void*, const char*);
  using TraceOpenFn = int (*)(void*, const char*);
  using TraceDumpFn = void (*)(void*, unsigned long long);
  using StatusFn = const int* (*)(void*);
  using TextFn = const char* (*)(void*);
  using ClearFn = void (*)(void*);

  CreateFn create = nullptr;
  DestroyFn destroy = nullptr;
  EvalFn eval = nullptr;
  PortFn port = nullptr;
  TraceOpenFn trace_open = nullptr;
  TraceDumpFn trace_dump = nullptr;
  StatusFn status = nullptr;
  TextFn where = nullptr, output = nullptr;
  ClearFn clear = nullptr;

 private:
  void* handle_ = nullptr;
};

// One role's bits of a live model's port: the whole port or a slice of it, in Verilator's storage
// (1, 2, 4 or 8 bytes, or 32-bit words for ports of over 64 bits). Writing a slice leaves the
// port's other bits as they are.
class PortAccess {
 public:
  PortAccess() = default;
  // `shift` and `width`: the slice's lowest bit and size within the port's storage.
  PortAccess(void* storage, int bytes, int shift, int width)
      : p_(storage), bytes_(bytes), shift_(shift), mask_(width >= 64 ? ~0ULL : (1ULL << width) - 1) {}
  bool bound() const { return p_ != nullptr; }
  std::uint64_t mask() const { return mask_; }
  std::uint64_t read() const {
    if (!p_) return 0;
    if (bytes_ == 0) return read_words();
    return (load() >> shift_) & mask_;
  }
  void write(std::uint64_t v) const {
    if (!p_) return;
    v &= mask_;
    if (bytes_ == 0) return write_words(v);
    const std::uint64_t whole = shift_ == 0 && mask_ == full_mask() ? v : (load() & ~(mask_ << shift_)) | (v << shift_);
    switch (bytes_) {
      case 1: *static_cast<std::uint8_t*>(p_) = static_cast<std::uint8_t>(whole); break;
      case 2: *static_cast<std::uint16_t*>(p_) = static_cast<std::uint16_t>(whole); break;
      case 4: *static_cast<std::uint32_t*>(p_) = static_cast<std::uint32_t>(whole); break;
      case 8: *static_cast<std::uint64_t*>(p_) = whole; break;
      default: break;
    }
  }

 private:
  std::uint64_t full_mask() const { return bytes_ >= 8 ? ~0ULL : (1ULL << (8 * bytes_)) - 1; }
  std::uint64_t load() const {
    switch (bytes_) {
      case 1: return *static_cast<const std::uint8_t*>(p_);
      case 2: return *static_cast<const std::uint16_t*>(p_);
      case 4: return *static_cast<const std::uint32_t*>(p_);
      case 8: return *static_cast<const std::uint64_t*>(p_);
      default: return 0;
    }
  }
  // Bit i of a wide port is bit i % 32 of word i / 32 (Verilator's VlWide).
  std::uint64_t read_words() const {
    const auto* w = static_cast<const std::uint32_t*>(p_);
    std::uint64_t v = 0;
    for (int i = 0; i < 64 && ((mask_ >> i) & 1); ++i) v |= static_cast<std::uint64_t>((w[(shift_ + i) / 32] >> ((shift_ + i) % 32)) & 1) << i;
    return v;
  }
  void write_words(std::uint64_t v) const {
    auto* w = static_cast<std::uint32_t*>(p_);
    for (int i = 0; i < 64 && ((mask_ >> i) & 1); ++i) {
      const std::uint32_t bit = 1u << ((shift_ + i) % 32);
      std::uint32_t& word = w[(shift_ + i) / 32];
      word = ((v >> i) & 1) ? word | bit : word & ~bit;
    }
  }

  void* p_ = nullptr;
  int bytes_ = 0;
  int shift_ = 0;
  std::uint64_t mask_ = 0;
};

// What the RTL itself did during the last evaluations: a $finish, or a verdict of its own ($stop,
// $fatal, $error, a failing assertion, or Verilator's own fatal error such as a loop that does not
// settle), with the file, line and message Verilator gave.
struct RtlEvent {
  enum class Kind { None = 0, Finish = 1, Stop = 2, Fatal = 3 };
  Kind kind = Kind::None;
  std::string where;    // "file.v:12"
  std::string message;  // the RTL's last line of output before it, e.g. "... Assertion failed in rx: boom"
};

// A live model (its own Verilator context); destroyed with the RTL's final blocks run.
class DutInstance {
 public:
  DutInstance(const DutLibrary& library, bool trace);
  ~DutInstance();
  DutInstance(const DutInstance&) = delete;
  DutInstance& operator=(const DutInstance&) = delete;

  void eval() { eval_(model_); }
  // Non-zero once the RTL has ended or judged itself (RtlEvent::Kind); one load, cheap to poll.
  int status() const { return *status_; }
  RtlEvent event() const;
  // The RTL's own output ($display, its messages) since the last call: at most 64 KiB of it, with
  // a line saying how much more was left out.
  std::string take_output();
  PortAccess port(const std::string& name, int bytes, int shift, int width) const;
  bool open_trace(const std::string& path);
  void dump(std::uint64_t time_ps) { library_.trace_dump(model_, time_ps); }

 private:
  const DutLibrary& library_;
  DutLibrary::EvalFn eval_;
  void* model_;
  const int* status_;
};

}  // namespace aesim
