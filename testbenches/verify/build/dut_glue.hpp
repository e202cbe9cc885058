#pragma once
#include <string>
#include <vector>

#include "build/port_list.hpp"

namespace aesim {

// The C interface between aesim and a Verilated receiver built at run time. The generated glue
// (dut_glue_source) exports these from the shared object; driver/dut_library loads them.
//   int   aesim_dut_abi(void)                      -> kDutGlueVersion
//   void* aesim_dut_create(int trace)              a model in its own VerilatedContext
//   void  aesim_dut_destroy(void*)                 runs the RTL's final blocks, closes any trace
//   void  aesim_dut_eval(void*)
//   void* aesim_dut_port(void*, const char* name)  the port's storage (CData/SData/IData/QData)
//   int   aesim_dut_trace_open(void*, const char* path)   Verilator's own VCD of every signal
//   void  aesim_dut_trace_dump(void*, unsigned long long time_ps)
// Bump the version whenever the glue changes: it is part of the cache key.
inline constexpr int kDutGlueVersion = 1;

std::string dut_glue_source(const std::vector<RtlPort>& ports);

}  // namespace aesim
