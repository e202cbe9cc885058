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
//   void* aesim_dut_port(void*, const char* name)  the port's storage (CData ... QData, VlWide)
//   int   aesim_dut_trace_open(void*, const char* path)   Verilator's own VCD of every signal
//   void  aesim_dut_trace_dump(void*, unsigned long long time_ps)
//   const int*  aesim_dut_status(void*)   0, or what ended the RTL: 1 $finish, 2 $stop/$error/a
//                                         failing assertion, 3 $fatal or Verilator's own fatal error
//   const char* aesim_dut_where(void*)    "file:line" of that
//   const char* aesim_dut_output(void*)   what the RTL printed since aesim_dut_clear (bounded)
//   void  aesim_dut_clear(void*)
// Bump the version whenever the glue changes: it is part of the cache key.
inline constexpr int kDutGlueVersion = 2;

// Verilator's hooks (VL_PRINTF, vl_stop, vl_fatal, vl_finish) redirected to the glue, so that
// the RTL's output and verdicts reach aesim instead of its stdout and abort(): force-included in
// Verilator's runtime and in the model.
std::string verilator_hooks_header();

std::string dut_glue_source(const std::vector<RtlPort>& ports);

}  // namespace aesim
