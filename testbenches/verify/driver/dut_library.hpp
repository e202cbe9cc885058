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

  CreateFn create = nullptr;
  DestroyFn destroy = nullptr;
  EvalFn eval = nullptr;
  PortFn port = nullptr;
  TraceOpenFn trace_open = nullptr;
  TraceDumpFn trace_dump = nullptr;

 private:
  void* handle_ = nullptr;
};

// One port of a live model: a pointer into Verilator's storage of 1, 2, 4 or 8 bytes.
class PortAccess {
 public:
  PortAccess() = default;
  PortAccess(void* storage, int bytes, int width)
      : p_(storage), bytes_(bytes), mask_(width >= 64 ? ~0ULL : (1ULL << width) - 1) {}
  bool bound() const { return p_ != nullptr; }
  std::uint64_t mask() const { return mask_; }
  std::uint64_t read() const {
    switch (bytes_) {
      case 1: return *static_cast<const std::uint8_t*>(p_);
      case 2: return *static_cast<const std::uint16_t*>(p_);
      case 4: return *static_cast<const std::uint32_t*>(p_);
      case 8: return *static_cast<const std::uint64_t*>(p_);
      default: return 0;
    }
  }
  void write(std::uint64_t v) const {
    v &= mask_;
    switch (bytes_) {
      case 1: *static_cast<std::uint8_t*>(p_) = static_cast<std::uint8_t>(v); break;
      case 2: *static_cast<std::uint16_t*>(p_) = static_cast<std::uint16_t>(v); break;
      case 4: *static_cast<std::uint32_t*>(p_) = static_cast<std::uint32_t>(v); break;
      case 8: *static_cast<std::uint64_t*>(p_) = v; break;
      default: break;
    }
  }

 private:
  void* p_ = nullptr;
  int bytes_ = 0;
  std::uint64_t mask_ = 0;
};

// A live model (its own Verilator context); destroyed with the RTL's final blocks run.
class DutInstance {
 public:
  DutInstance(const DutLibrary& library, bool trace);
  ~DutInstance();
  DutInstance(const DutInstance&) = delete;
  DutInstance& operator=(const DutInstance&) = delete;

  void eval() { eval_(model_); }
  PortAccess port(const std::string& name, int bytes, int width) const;
  bool open_trace(const std::string& path);
  void dump(std::uint64_t time_ps) { library_.trace_dump(model_, time_ps); }

 private:
  const DutLibrary& library_;
  DutLibrary::EvalFn eval_;
  void* model_;
};

}  // namespace aesim
