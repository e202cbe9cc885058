#include "driver/dut_library.hpp"

#include <dlfcn.h>

#include <cstring>

#include <fmt/format.h>

#include "build/dut_glue.hpp"
#include "aesim/errors/input_error.hpp"

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
  status = reinterpret_cast<StatusFn>(symbol("aesim_dut_status"));
  where = reinterpret_cast<TextFn>(symbol("aesim_dut_where"));
  output = reinterpret_cast<TextFn>(symbol("aesim_dut_output"));
  clear = reinterpret_cast<ClearFn>(symbol("aesim_dut_clear"));
}

DutLibrary::~DutLibrary() {
  if (handle_) ::dlclose(handle_);
}

DutInstance::DutInstance(const DutLibrary& library, bool trace)
    : library_(library), eval_(library.eval), model_(library.create(trace ? 1 : 0)), status_(library.status(model_)) {}

DutInstance::~DutInstance() { library_.destroy(model_); }

PortAccess DutInstance::port(const std::string& name, int bytes, int shift, int width) const {
  return PortAccess(library_.port(model_, name.c_str()), bytes, shift, width);
}

// The last complete line of the output before the event: Verilator prints an assertion's message
// ("%Error: rx.v:12: Assertion failed in rx: boom") just before it stops.
RtlEvent DutInstance::event() const {
  RtlEvent e;
  e.kind = static_cast<RtlEvent::Kind>(*status_);
  e.where = library_.where(model_);
  std::string text = library_.output(model_);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const auto nl = text.rfind('\n');
  e.message = nl == std::string::npos ? text : text.substr(nl + 1);
  // "[0] %Error: rx.v:12: Assertion failed in rx: boom" -> "rx.v:12: Assertion failed in rx: boom"
  if (!e.message.empty() && e.message.front() == '[') {
    const auto close = e.message.find("] ");
    if (close != std::string::npos) e.message.erase(0, close + 2);
  }
  for (const char* tag : {"%Error: ", "%Fatal: ", "%Warning: "}) {
    if (e.message.rfind(tag, 0) == 0) e.message.erase(0, std::strlen(tag));
  }
  if (e.message.empty()) e.message = e.where;
  return e;
}

std::string DutInstance::take_output() {
  std::string text = library_.output(model_);
  library_.clear(model_);
  return text;
}

bool DutInstance::open_trace(const std::string& path) { return library_.trace_open(model_, path.c_str()) != 0; }

}  // namespace aesim
