#pragma once
#include <string>

#include "description/receiver_description.hpp"

namespace aesim {

// A receiver written in VHDL, turned into the Verilog that Verilator, yosys and Icarus read:
// GHDL's synthesis (`ghdl --synth --out=verilog`, its generics set from `parameters`) elaborates
// the top entity into one Verilog module of the same name and ports, spelt as the VHDL declares
// them. The description that comes back names that file as its only source, the generics already
// applied (no parameters, no [formal] parameters: see vhdl_for_the_proof), and its top and port
// names spelt as the module's (VHDL's names match whatever their case, so the description's may
// differ in case). Under a Verilog top, each VHDL entity the Verilog names is converted with the
// generics its instances set and built beside the Verilog. A description without VHDL comes back
// as it is. The file is cached under `cache_dir` by a hash of the sources, the generics and
// GHDL's version. Throws InputError for a VHDL top beside Verilog, generics GHDL cannot be given,
// a missing GHDL, or VHDL GHDL cannot synthesise (its first error, and its log's path).
ReceiverDescription with_vhdl_as_verilog(const ReceiverDescription& d, const std::string& cache_dir);

// The description the proof runs: for a design all in VHDL with `[formal] parameters`, the VHDL
// converted again with them over `parameters` (narrower generics for the proof, as a Verilog
// design's [formal] parameters are applied to it); otherwise `converted` as it is.
ReceiverDescription vhdl_for_the_proof(const ReceiverDescription& written, const ReceiverDescription& converted,
                                       const std::string& cache_dir);

// Whether a source file is VHDL, by its extension (.vhd, .vhdl).
bool is_vhdl_source(const std::string& path);

}  // namespace aesim
