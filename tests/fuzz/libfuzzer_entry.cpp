// One libFuzzer binary per target: AESIM_FUZZ_TARGET names it (tests/fuzz/CMakeLists.txt).
#include "fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aesim::fuzz::AESIM_FUZZ_TARGET(data, size);
}

// libsystemc.so (linked through the model library) refers to sc_main from its own main(); the
// fuzz binaries start in libFuzzer's main instead and never run a simulation.
extern "C" int sc_main(int, char**) { return 1; }
