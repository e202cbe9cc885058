#pragma once
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"

namespace aesim {

struct DutBuildOptions {
  std::string cache_dir;  // built models, one folder per hash of sources and options
  std::string log_dir;    // where the tools' logs go when the RTL does not build
  bool progress = true;   // one line per step on stderr while building
  // With Verilator's tracing (--trace), for the rerun that writes failure.vcd. Tracing costs
  // about a quarter of the speed even when no trace is open, so runs use the model without it.
  bool trace = false;
  // Let the RTL call $system (a shell command on this machine); refused otherwise.
  bool allow_system_tasks = false;
};

// A team's receiver Verilated as a shared object that aesim loads (driver/dut_library).
struct DutBuild {
  std::string library;  // path of the shared object
  std::vector<RtlPort> ports;
  bool cached = false;
  double seconds = 0;  // wall time spent here
};

// Verilates and compiles the description's RTL, or finds it in the cache: the key hashes the
// sources, include files, defines, parameters, the top, Verilator's version and the compiler.
// A build goes to a temporary folder renamed into the cache when it is complete, so concurrent
// or interrupted runs never see half a model. RTL that does not build is an InputError naming
// the first error's file and line, with the tool's log kept in options.log_dir.
DutBuild build_dut(const ReceiverDescription& description, const DutBuildOptions& options);

// Removes what runs that died (a signal, a kill) left in the cache: its tmp*.PID folders whose
// process is gone.
void remove_dead_temps(const std::string& cache);

// $AESIM_CACHE_DIR, else $XDG_CACHE_HOME/aesim, else ~/.cache/aesim.
std::string default_cache_dir();

}  // namespace aesim
