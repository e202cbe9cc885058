#include "driver/dut_library.hpp"

#include <dlfcn.h>

#include <fmt/format.h>

#include "build/dut_glue.hpp"
#include "errors/input_error.hpp"

namespace aesim {

DutLibrary::DutLibrary(const std::string& path) {
  // RTLD_LOCAL: each model keeps its symbols (and its Verilator runtime) to itself.
  handle_ = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) throw InputError(fmt::format("cannot load the receiver model {}: {}", path, ::dlerror()));
  auto symbol = [&](const char* name) {
    void* s = ::dlsym(handle_, name);
    if (!s) throw InputError(fmt::format("receiver model {} lacks {} (delete the cache entry)", path, name));
    return s;
  };
  const auto abi = reinterpret_cast<int (*)()>(symbol("aesim_dut_abi"));
  if (abi() != kDutGlueVersion) throw InputError(fmt::format("receiver model {} is of another aesim version", path));
  create = reinterpret_cast<CreateFn>(symbol("aesim_dut_create"));
  destroy = reinterpret_cast<DestroyFn>(symbol("aesim_dut_destroy"));
  eval = reinterpret_cast<EvalFn>(symbol("aesim_dut_eval"));
  port = reinterpret_cast<PortFn>(symbol("aesim_dut_port"));
  trace_open = reinterpret_cast<TraceOpenFn>(symbol("aesim_dut_trace_open"));
  trace_dump = reinterpret_cast<TraceDumpFn>(symbol("aesim_dut_trace_dump"));
}

DutLibrary::~DutLibrary() {
  if (handle_) ::dlclose(handle_);
}

DutInstance::DutInstance(const DutLibrary& library, bool trace)
    : library_(library), eval_(library.eval), model_(library.create(trace ? 1 : 0)) {}

DutInstance::~DutInstance() { library_.destroy(model_); }

PortAccess DutInstance::port(const std::string& name, int bytes, int width) const {
  return PortAccess(library_.port(model_, name.c_str()), bytes, width);
}

bool DutInstance::open_trace(const std::string& path) { return library_.trace_open(model_, path.c_str()) != 0; }

}  // namespace aesim
