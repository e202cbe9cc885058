// Entry point of every aesim executable (the program, the tests, the benchmarks).
// libsystemc supplies a main() that prints the kernel's banner before sc_main runs; this one,
// which the linker prefers, silences it first, then starts SystemC as usual.
#include <cstdlib>
#include <systemc>

int main(int argc, char* argv[]) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return sc_core::sc_elab_and_sim(argc, argv);
}
