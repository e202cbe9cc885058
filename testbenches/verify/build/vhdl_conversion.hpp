#pragma once
#include <string>

#include "description/receiver_description.hpp"

namespace aesim {

// A receiver written in VHDL, turned into the Verilog that Verilator, yosys and Icarus read:
// GHDL's synthesis (`ghdl --synth --out=verilog`, its generics set from `parameters`) elaborates
// the top entity into one Verilog module of the same name and ports, spelt as the VHDL declares
// them. The description that comes back names that file as its only source, the generics already
// applied (no parameters), and its top and port names spelt as the module's (VHDL's names match
// whatever their case, so the description's may differ in case); a description without VHDL
// comes back as it is. The file is cached under `cache_dir` by a hash of the sources, the generics
// and GHDL's version. Throws InputError for a description mixing VHDL with Verilog, `[formal]
// parameters` on VHDL (generics are set once), a missing GHDL, or VHDL GHDL cannot synthesise
// (its first error, and its log's path).
ReceiverDescription with_vhdl_as_verilog(const ReceiverDescription& d, const std::string& cache_dir);

// Whether a source file is VHDL, by its extension (.vhd, .vhdl).
bool is_vhdl_source(const std::string& path);

}  // namespace aesim
