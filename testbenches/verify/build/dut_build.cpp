#include "build/dut_build.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "build/dut_glue.hpp"
#include "build/tool_output.hpp"
#include "description/rtl_folder_key.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/content_hash.hpp"
#include "aesim/files/scratch_folder.hpp"
#include "aesim/files/scratch_text.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// A tool's output captured through a file (no shell, no pipe to drain).
// "%Error: /x/rx.v:12:5: syntax error ..." -> "rx.v:12: syntax error ...".
std::string first_error(const std::string& log, const std::string& tool) {
  std::istringstream lines(log);
  std::string line;
  while (std::getline(lines, line)) {
    const auto at = line.find("%Error");
    const auto gcc = line.find(": error: ");
    if (at != std::string::npos) {
      std::string rest = line.substr(line.find(':', at) + 1);
      while (!rest.empty() && rest.front() == ' ') rest.erase(rest.begin());
      // file:line:col: message -> file:line: message
      const auto c1 = rest.find(':');
      const auto c2 = c1 == std::string::npos ? c1 : rest.find(':', c1 + 1);
      const auto c3 = c2 == std::string::npos ? c2 : rest.find(':', c2 + 1);
      if (c3 != std::string::npos && std::all_of(rest.begin() + static_cast<long>(c2) + 1, rest.begin() + static_cast<long>(c3), ::isdigit)) {
        rest = rest.substr(0, c2) + rest.substr(c3);
      }
      return rest;
    }
    if (gcc != std::string::npos) return line;
  }
  return fmt::format("{} failed (see its log)", tool);
}

class Progress {
 public:
  explicit Progress(bool on) : on_(on), start_(std::chrono::steady_clock::now()) {}
  void step(const std::string& what) const {
    if (!on_) return;
    std::fprintf(stderr, "  [%5.1f s] %s\n", seconds(), what.c_str());
    std::fflush(stderr);
  }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool on_;
  std::chrono::steady_clock::time_point start_;
};

struct Toolchain {
  std::string verilator_version, verilator_root, compiler;
};

Toolchain toolchain(const fs::path& scratch) {
  Toolchain t;
  if (!program_available("verilator")) throw InputError("verilator is not installed (scripts/setup installs it)");
  t.verilator_version = tool_output("verilator", {"--version"}, scratch);
  t.verilator_root = tool_output("verilator", {"--getenv", "VERILATOR_ROOT"}, scratch);
  t.compiler = AESIM_CXX;
  if (!program_available(t.compiler)) t.compiler = "c++";
  return t;
}

// Flags of the model and of Verilator's runtime alike (verilated.mk's, for a C++ model with VCD
// tracing). Hidden visibility and -Bsymbolic at the link keep the library's Verilator runtime
// its own: aesim itself links another (a SystemC one) that must not be interposed.
std::vector<std::string> compile_flags(const Toolchain& t, bool trace, const fs::path& hooks) {
  const std::string on = trace ? "1" : "0";
  return {"-std=c++17", "-O2", "-fPIC", "-fvisibility=hidden", "-faligned-new", "-w",
          "-DVM_COVERAGE=0", "-DVM_SC=0", "-DVM_TRACE=" + on, "-DVM_TRACE_FST=0", "-DVM_TRACE_VCD=" + on,
          "-include", hooks.string(),
          "-I" + t.verilator_root + "/include", "-I" + t.verilator_root + "/include/vltstd"};
}

// The hooks header, in the cache under a name made of its own hash (so a changed header is a
// new file, and the flags naming it a new cache key).
fs::path hooks_header(const fs::path& cache) {
  const std::string text = verilator_hooks_header();
  const fs::path path = cache / ("vl_hooks-" + content_hash_hex(text) + ".h");
  if (fs::is_regular_file(path)) return path;
  const fs::path temp = cache / fmt::format("tmp-hooks.{}", ::getpid());
  write_scratch_text(temp, text);
  fs::rename(temp, path);
  return path;
}

// What the RTL would run on this machine: $system (a shell command) and DPI imports (C functions
// aesim does not link). Found in Verilator's output, so no macro or generate block hides them.
void refuse_host_calls(const fs::path& obj, bool allow_system_tasks) {
  const std::regex dpi(R"(// DPI import at ([^\n]*))");
  for (const auto& e : fs::directory_iterator(obj)) {
    const std::string name = e.path().filename().string();
    if (name.size() < 4) continue;
    const std::string text = read_scratch_text(e.path());
    std::smatch m;
    if (name.find("__Dpi.h") != std::string::npos && std::regex_search(text, m, dpi)) {
      throw InputError(fmt::format("receiver RTL imports a C function (DPI import at {}); aesim verify links no C code", m[1].str()));
    }
    if (!allow_system_tasks && e.path().extension() == ".cpp" && text.find("VL_SYSTEM_I") != std::string::npos) {
      throw InputError("receiver RTL calls $system, which would run a shell command; pass --allow-system-tasks to let it");
    }
  }
}

// Runs compiler jobs two at a time; returns the first failure's index, or -1.
int compile_all(const std::string& compiler, const std::vector<std::vector<std::string>>& jobs, const fs::path& log) {
  std::vector<pid_t> running;
  std::vector<std::size_t> index;
  int failed = -1;
  auto reap = [&] {
    const int status = wait_child(running.front());
    if (status != 0 && failed < 0) failed = static_cast<int>(index.front());
    running.erase(running.begin());
    index.erase(index.begin());
  };
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (running.size() == 2) reap();
    const fs::path job_log = log.string() + "." + std::to_string(i);
    running.push_back(spawn_child(compiler, jobs[i], {job_log.string(), job_log.string()}));
    index.push_back(i);
  }
  while (!running.empty()) reap();
  std::string all;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const fs::path job_log = log.string() + "." + std::to_string(i);
    all += read_scratch_text(job_log);
    fs::remove(job_log);
  }
  write_scratch_text(log, all);
  return failed;
}

// Verilator's runtime, compiled once per Verilator and compiler for every model in the cache.
std::vector<std::string> runtime_objects(const fs::path& cache, const Toolchain& t, bool trace, const fs::path& hooks,
                                         const Progress& progress) {
  std::vector<std::string> units = {"verilated", "verilated_threads"};
  if (trace) units.push_back("verilated_vcd_c");
  std::string key = t.verilator_version + "\n" + t.verilator_root + "\n" + t.compiler + "\n";
  for (const std::string& flag : compile_flags(t, trace, hooks)) key += flag + " ";
  const fs::path dir = cache / ("runtime-" + content_hash_hex(key));
  std::vector<std::string> objects;
  for (const std::string& u : units) objects.push_back((dir / (u + ".o")).string());
  if (fs::is_directory(dir)) return objects;
  progress.step("compiling Verilator's runtime (once for every receiver)");
  const fs::path work = cache / fmt::format("tmp-runtime.{}", ::getpid());
  fs::remove_all(work);
  fs::create_directories(work);
  std::vector<std::vector<std::string>> jobs;
  for (const std::string& u : units) {
    std::vector<std::string> args = compile_flags(t, trace, hooks);
    for (const std::string& a : {std::string("-c"), t.verilator_root + "/include/" + u + ".cpp", std::string("-o"),
                                 (work / (u + ".o")).string()}) {
      args.push_back(a);
    }
    jobs.push_back(args);
  }
  if (compile_all(t.compiler, jobs, work / "compile.log") >= 0) {
    throw std::runtime_error(fmt::format("compiling Verilator's runtime failed; see {}", (work / "compile.log").string()));
  }
  std::error_code ec;
  fs::rename(work, dir, ec);
  if (ec) fs::remove_all(work);  // another run finished it first
  return objects;
}

std::vector<std::string> verilator_args(const ReceiverDescription& d, const fs::path& obj, bool trace) {
  // --assert: the RTL's own assertions are its verdicts, so they are compiled in.
  std::vector<std::string> args = {"--cc", "-O3", "--assert", "-Wno-fatal", "-Wno-lint", "-Wno-style", "--prefix", "Vdut",
                                   "--top-module", d.top, "--Mdir", obj.string()};
  if (trace) args.push_back("--trace");
  for (const std::string& dir : d.include_dirs) args.push_back("-I" + dir);
  for (const auto& [k, v] : d.defines) args.push_back(v.empty() ? "+define+" + k : "+define+" + k + "=" + v);
  for (const auto& [k, v] : d.parameters) args.push_back("-G" + k + "=" + v);
  for (const std::string& s : d.sources) args.push_back(s);
  return args;
}

std::string cache_key(const ReceiverDescription& d, const Toolchain& t, bool trace, const fs::path& hooks,
                      bool allow_system_tasks) {
  std::string all = "aesim-dut-glue-v" + std::to_string(kDutGlueVersion) + (trace ? " traced\n" : "\n") +
                    t.verilator_version + "\n" + t.verilator_root + "\n" + t.compiler + "\ntop " + d.top + "\n" +
                    (allow_system_tasks ? "system tasks allowed\n" : "");
  for (const std::string& flag : compile_flags(t, trace, hooks)) all += flag + " ";
  for (const std::string& arg : verilator_args(d, "", trace)) all += arg + " ";
  for (const std::string& s : d.sources) all += "source " + s + "\n" + read_scratch_text(s) + "\n";
  for (const std::string& dir : d.include_dirs) {
    add_rtl_folder_to_key(all, dir, RtlFolderFiles::All, [](const fs::path& f) { return f.string(); }, "include_dirs");
  }
  for (const auto& [k, v] : d.defines) all += "define " + k + "=" + v + "\n";
  for (const auto& [k, v] : d.parameters) all += "parameter " + k + "=" + v + "\n";
  return content_hash_hex(all);
}


[[noreturn]] void build_failed(const std::string& tool, const fs::path& log, const DutBuildOptions& options) {
  std::string kept = log.string();
  if (!options.log_dir.empty()) {
    std::error_code ec;
    fs::create_directories(options.log_dir, ec);
    const fs::path dest = fs::path(options.log_dir) / log.filename();
    fs::copy_file(log, dest, fs::copy_options::overwrite_existing, ec);
    if (!ec) kept = dest.string();
  }
  const std::string error = first_error(read_scratch_text(log), tool);
  // A top whose ports are an interface's (bus.req): the ports aesim drives must be plain ones.
  const std::string advice = error.find("Interfaced port on top level module") != std::string::npos
                                 ? "; aesim drives a top's plain ports: name as top a module of plain ports that makes the "
                                   "interface and connects it to this one (docs/verify.md, a top with interface ports)"
                                 : "";
  throw InputError(fmt::format("receiver RTL does not build: {}{} ({}'s log: {})", error, advice, tool, kept));
}

}  // namespace

void remove_dead_temps(const std::string& cache) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(cache, ec)) {
    const std::string name = e.path().filename().string();
    const auto dot = name.rfind('.');
    if (name.rfind("tmp", 0) != 0 || dot == std::string::npos) continue;
    const std::string pid = name.substr(dot + 1);
    if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t owner = static_cast<pid_t>(std::stol(pid));
    if (owner == ::getpid() || ::kill(owner, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    fs::remove_all(e.path(), ignored);
  }
}

std::string default_cache_dir() {
  if (const char* dir = std::getenv("AESIM_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/aesim";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/aesim";
  return ".aesim-cache";
}

DutBuild build_dut(const ReceiverDescription& d, const DutBuildOptions& options) {
  const Progress progress(options.progress);
  const fs::path cache = options.cache_dir;
  std::error_code ec;
  fs::create_directories(cache, ec);
  if (ec) throw InputError(fmt::format("cache folder '{}': {}", cache.string(), ec.message()));
  remove_dead_temps(cache.string());
  const ScratchFolder scratch(cache / fmt::format("tmp.{}", ::getpid()));
  const fs::path& work = scratch.path();

  const Toolchain t = toolchain(work);
  const fs::path hooks = hooks_header(cache);
  const fs::path entry =
      cache / ((options.trace ? "traced-" : "model-") + cache_key(d, t, options.trace, hooks, options.allow_system_tasks));
  DutBuild out;
  out.library = (entry / "dut.so").string();
  if (fs::is_regular_file(out.library) && fs::is_regular_file(entry / "ports.txt")) {
    out.ports = parse_port_list_text(read_scratch_text(entry / "ports.txt"));
    out.cached = true;
    out.seconds = progress.seconds();
    return out;
  }
  if (options.progress) {
    std::fprintf(stderr, "aesim verify: building %s%s (first run of these sources; cached in %s)\n", d.top.c_str(),
                 options.trace ? " with Verilator's tracing" : "", entry.string().c_str());
  }
  progress.step("verilator --cc " + d.top);
  const fs::path obj = work / "obj";
  if (run_child("verilator", verilator_args(d, obj, options.trace), {(work / "verilator.log").string(), (work / "verilator.log").string()}) != 0) {
    build_failed("verilator", work / "verilator.log", options);
  }
  refuse_host_calls(obj, options.allow_system_tasks);
  out.ports = ports_in_verilated_header(read_scratch_text(obj / "Vdut.h"));
  write_scratch_text(work / "dut_glue.cpp", dut_glue_source(out.ports));
  std::vector<fs::path> generated;
  for (const auto& e : fs::directory_iterator(obj)) {
    if (e.path().extension() == ".cpp") generated.push_back(e.path());
  }
  std::sort(generated.begin(), generated.end());
  // One translation unit, as Verilator's own makefile builds (Vdut__ALL.cpp): its headers are
  // most of the compile time.
  std::string unity;
  for (const fs::path& g : generated) unity += "#include \"" + g.string() + "\"\n";
  unity += "#include \"" + (work / "dut_glue.cpp").string() + "\"\n";
  write_scratch_text(work / "model.cpp", unity);

  const std::vector<std::string> runtime = runtime_objects(cache, t, options.trace, hooks, progress);
  progress.step("compiling the model");
  std::vector<std::string> args = compile_flags(t, options.trace, hooks);
  for (const std::string& a : {"-I" + obj.string(), std::string("-c"), (work / "model.cpp").string(), std::string("-o"),
                               (work / "model.o").string()}) {
    args.push_back(a);
  }
  if (compile_all(t.compiler, {args}, work / "compile.log") >= 0) build_failed(t.compiler, work / "compile.log", options);
  progress.step("linking");
  std::vector<std::string> link = {"-shared", "-fPIC", "-Wl,-Bsymbolic", "-o", (work / "dut.so").string(),
                                   (work / "model.o").string()};
  link.insert(link.end(), runtime.begin(), runtime.end());
  link.push_back("-pthread");
  if (compile_all(t.compiler, {link}, work / "link.log") >= 0) build_failed(t.compiler, work / "link.log", options);
  write_scratch_text(work / "ports.txt", port_list_text(out.ports));

  const fs::path staged = cache / fmt::format("tmp-entry.{}", ::getpid());
  fs::remove_all(staged);
  fs::create_directories(staged);
  fs::rename(work / "dut.so", staged / "dut.so");
  fs::rename(work / "ports.txt", staged / "ports.txt");
  fs::rename(work / "verilator.log", staged / "verilator.log");
  fs::rename(staged, entry, ec);
  if (ec) fs::remove_all(staged);  // another run cached the same model first
  progress.step("done");
  out.seconds = progress.seconds();
  return out;
}

}  // namespace aesim
